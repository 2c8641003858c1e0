#!/usr/bin/env bash
# Install every Debian 12 package voxr needs to build, test, benchmark and view. Idempotent: packages
# already present are skipped, so a second run costs one dpkg query. python3-dev and python3-venv: the
# Python package (pip install . in a venv; its own dependencies come from PyPI, scripts/python-check.sh).
set -euo pipefail

packages=(
  build-essential cmake pkg-config clang-format
  pocl-opencl-icd ocl-icd-opencl-dev opencl-clhpp-headers opencl-c-headers clinfo
  libglm-dev libcgal-dev libassimp-dev nlohmann-json3-dev libfmt-dev libcli11-dev
  libpng-dev libopenexr-dev libstb-dev libopenimageio-dev openimageio-tools libembree-dev libvtk9-dev
  libgtest-dev libbenchmark-dev python3-matplotlib xvfb xauth libopenvdb-dev libboost-iostreams-dev libminizip-dev
  python3-dev python3-venv
  glmark2-data libcgal-demo
)

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q '^install ok installed$' || missing+=("$p")
done

if [ ${#missing[@]} -eq 0 ]; then
  echo "install-deps: all ${#packages[@]} packages present"
  exit 0
fi

if [ "$(id -u)" -ne 0 ]; then
  echo "install-deps: missing packages: ${missing[*]}; run this script as root" >&2
  exit 1
fi

echo "install-deps: installing ${missing[*]}"
export DEBIAN_FRONTEND=noninteractive
apt-get update -qq
apt-get install -y -qq --no-install-recommends "${missing[@]}"
