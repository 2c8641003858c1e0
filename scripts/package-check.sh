#!/usr/bin/env bash
# The installed C++ package (docs/library.md), as CI checks it after the Release build:
#   1. cmake --install BUILD into BUILD/install (the runtime and devel components);
#   2. only the public headers, libvoxr and libvoxr_render exporting only voxr:: API symbols, no library of
#      the internals needed at run time that the package does not bring (ldd);
#   3. examples/consumer configured against the package alone (CMAKE_PREFIX_PATH=BUILD/install) in
#      BUILD/consumer, built and run; its output checked (exit code, dims, voxel counts, error line, image).
# Usage: scripts/package-check.sh [BUILD]   (default: build)
set -euo pipefail
cd "$(dirname "$0")/.."
build=${1:-build}
build=$(cd "$build" && pwd)
prefix=$build/install
start=$(date +%s.%N)
fail() { echo "package-check: $*" >&2; exit 1; }

rm -rf "$prefix"
cmake --install "$build" --prefix "$prefix" --component runtime >/dev/null
cmake --install "$build" --prefix "$prefix" --component devel >/dev/null

for f in lib/libvoxr.so lib/libvoxr.so.0 lib/libvoxr_render.so lib/libvoxr_render.so.0 bin/voxr bin/voxr-render \
         include/voxr/voxr.h include/voxr/error.h include/voxr/render.h \
         lib/cmake/voxr/voxrConfig.cmake lib/cmake/voxr/voxrConfigVersion.cmake lib/cmake/voxr/voxrTargets.cmake; do
  [[ -e $prefix/$f ]] || fail "$prefix/$f is missing"
done
headers=$(cd "$prefix/include" && find . -type f | sort | tr '\n' ' ')
[[ $headers == "./voxr/error.h ./voxr/render.h ./voxr/voxr.h " ]] || fail "unexpected headers: $headers"

# Every exported symbol is the public API's (include/voxr/*.h): its functions and classes, with their typeinfo
# and vtables; the internals (voxr's own host/ classes, fmt, the OpenCL wrapper, std:: template instances)
# stay hidden.
api='voxr::(render|version|devices|voxelize|voxelize_file|Context|VoxelVolume|Error|InternalError)\b'
for lib in libvoxr.so libvoxr_render.so; do
  stray=$(nm -D --defined-only "$prefix/lib/$lib" | awk '$2 != "A" {print $3}' | c++filt |
          grep -v -E "^((typeinfo (name )?|vtable |VTT )for )?$api" || true)
  [[ -z $stray ]] || fail "$lib exports more than the API: $(echo "$stray" | head -5 | tr '\n' ';')"
  missing=$(ldd "$prefix/lib/$lib" | grep 'not found' || true)
  [[ -z $missing ]] || fail "$lib: $missing"
done

rm -rf "$build/consumer"
cmake -S examples/consumer -B "$build/consumer" -DCMAKE_PREFIX_PATH="$prefix" -DCMAKE_BUILD_TYPE=Release \
  >"$build/consumer.log" 2>&1 || { cat "$build/consumer.log"; fail "configuring examples/consumer failed"; }
cmake --build "$build/consumer" >>"$build/consumer.log" 2>&1 || { cat "$build/consumer.log"; fail "building examples/consumer failed"; }
# The program finds libvoxr through the imported targets' RPATH in the build tree, the installed one only.
# (ldd's output is read whole: `ldd | grep -q` fails under pipefail when grep stops reading early.)
libs=$(ldd "$build/consumer/voxr_consumer")
grep -qF "$prefix/lib/libvoxr.so.0" <<<"$libs" || fail "voxr_consumer does not load $prefix/lib/libvoxr.so"

mkdir -p "$build/pocl-cache"
out=$(POCL_CACHE_DIR=$build/pocl-cache "$build/consumer/voxr_consumer") || { echo "$out"; fail "voxr_consumer failed"; }
echo "$out"
expect() { grep -qxF -- "$1" <<<"$out" || fail "expected the line '$1'"; }
expect "voxr 0.1.0"
expect "dims 32 17 17"
expect "voxels set 2498, inside 9248"   # as `voxr voxelize box.obj --res 32 --solid flood`
expect "error: unknown method 'sideways' (methods: hybrid, slice, grid, slicemap)"
# The mean of the 64x48 default-scene image: 0.4347 0.4648 0.4957 1.0000 with PoCL on the CPU (and
# `voxr render --size 64x48`); within 0.005 on another device.
image=$(grep -E '^image ' <<<"$out" || true)
awk -v want="0.4347 0.4648 0.4957 1.0000" '
  $1 == "image" && $2 == "64x48," { split(want, w, " "); for (i = 1; i <= 4; ++i) if ((d = $(4 + i) - w[i]) > 0.005 || d < -0.005) exit 1; ok = 1 }
  END { exit !ok }' <<<"$image" || fail "unexpected image line: '$image'"
printf 'package-check: ok (%.1f s)\n' "$(echo "$(date +%s.%N) - $start" | bc)"
