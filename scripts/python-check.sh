#!/usr/bin/env bash
# The Python package's check (docs/python.md), run by the README's test command after the Release build in
# build/: a venv in build/venv (Debian's /usr/bin/python3, reused when present), the test dependencies, then
# `pip install .` configured to reuse build/ (same generator, build type and cache), so only the extension
# compiles and links, then pytest python/tests.
# usage: scripts/python-check.sh [BUILD_DIR]   (default: build; an absolute path or one under the repository)
set -euo pipefail
cd "$(dirname "$0")/.."
root=$PWD
build=$(realpath -m "${1:-build}")
venv=$build/venv
start=$(date +%s.%N)

if [[ ! -x $venv/bin/python ]]; then
  /usr/bin/python3 -m venv "$venv"
  "$venv/bin/python" -m pip install -q --upgrade pip
fi
# Test dependencies, and the build backend itself (the install below runs without build isolation so that
# build/ keeps one nanobind and one Python across runs).
"$venv/bin/python" -m pip install -q --disable-pip-version-check numpy pytest trimesh tqdm "dask[distributed]" \
  "scikit-build-core>=0.10" "nanobind>=2.0"

args=(--no-build-isolation --disable-pip-version-check -q)
if [[ -f $build/CMakeCache.txt ]]; then
  # Reuse build/: the generator it was made with (scripts/build.sh: CMake's default, Unix Makefiles), Release,
  # and the options it has (pyproject.toml turns tests/bench/viewer off for a fresh wheel build; a CI tree
  # keeps them on). The ccache launcher, if the tree has one, stays in its cache.
  cache() { sed -n "s/^$1:[A-Z]*=//p" "$build/CMakeCache.txt"; }
  export CMAKE_GENERATOR=${CMAKE_GENERATOR:-$(cache CMAKE_GENERATOR)}
  args+=(--config-settings="build-dir=$build" --config-settings="cmake.build-type=$(cache CMAKE_BUILD_TYPE)")
  for option in VOXR_BUILD_TESTS VOXR_BUILD_BENCH VOXR_BUILD_VIEWER VOXR_WITH_OPENVDB; do
    value=$(cache $option)
    [[ -n $value ]] && args+=(--config-settings="cmake.define.$option=$value")
  done
fi
export CMAKE_BUILD_PARALLEL_LEVEL=${CMAKE_BUILD_PARALLEL_LEVEL:-$(nproc)}
"$venv/bin/python" -m pip install "${args[@]}" "$root"
installed=$(date +%s.%N)

# Tests from outside the source tree so `import voxr` is the installed package, not python/voxr.
export POCL_CACHE_DIR=${POCL_CACHE_DIR:-$build/pocl-cache}
export VOXR_TEST_DATA=${VOXR_TEST_DATA:-$root/data}
(cd "$build" && "$venv/bin/python" -m pytest -q -rs "$root/python/tests")
end=$(date +%s.%N)
awk -v s="$start" -v i="$installed" -v e="$end" 'BEGIN { printf "python-check: install %.1f s, tests %.1f s\n", i - s, e - i }'
