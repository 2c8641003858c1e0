#!/usr/bin/env bash
# Copy the Debian-packaged test meshes into data/meshes (or the folder given as the first argument):
#   bunny.obj                                   from glmark2-data (/usr/share/glmark2/models)
#   armadillo.off bunny00.off ChineseDragon-10kv.off refined_elephant.off mech-holes-shark.off
#                                               from libcgal-demo (/usr/share/doc/libcgal-dev/data.tar.gz)
# No network beyond apt: missing packages are installed when running as root, otherwise named.
# Idempotent: files already present and identical are left alone.
set -euo pipefail

repo="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
dest="${1:-$repo/data/meshes}"

packages=(glmark2-data libcgal-demo)
bunny_src=/usr/share/glmark2/models/bunny.obj
cgal_tar=/usr/share/doc/libcgal-dev/data.tar.gz
cgal_meshes=(armadillo.off bunny00.off ChineseDragon-10kv.off refined_elephant.off mech-holes-shark.off)

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q '^install ok installed$' || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  if [ "$(id -u)" -ne 0 ]; then
    echo "fetch-meshes: missing packages: ${missing[*]}; install them with" >&2
    echo "  sudo apt-get install --no-install-recommends ${missing[*]}" >&2
    exit 1
  fi
  echo "fetch-meshes: installing ${missing[*]}"
  export DEBIAN_FRONTEND=noninteractive
  apt-get install -y -qq --no-install-recommends "${missing[@]}" ||
    { apt-get update -qq && apt-get install -y -qq --no-install-recommends "${missing[@]}"; }
fi

for f in "$bunny_src" "$cgal_tar"; do
  [ -f "$f" ] || { echo "fetch-meshes: $f is missing although its package is installed" >&2; exit 1; }
done

mkdir -p "$dest"

# Copies $1 to $2 unless $2 already has the same content.
install_file() {
  if cmp -s "$1" "$2"; then
    echo "fetch-meshes: $(basename "$2") up to date"
  else
    cp "$1" "$2.tmp" && mv "$2.tmp" "$2"
    echo "fetch-meshes: wrote $2"
  fi
}

install_file "$bunny_src" "$dest/bunny.obj"

tmp="$(mktemp -d)"
trap 'rm -rf "$tmp"' EXIT
members=()
for m in "${cgal_meshes[@]}"; do members+=("data/meshes/$m"); done
tar -xzf "$cgal_tar" -C "$tmp" "${members[@]}"
for m in "${cgal_meshes[@]}"; do install_file "$tmp/data/meshes/$m" "$dest/$m"; done

echo "fetch-meshes: ${#cgal_meshes[@]} CGAL meshes and bunny.obj in $dest"
