#!/usr/bin/env bash
# Fuzz every mesh reader with libFuzzer (ASan + UBSan): OFF, OBJ, PLY, STL with voxr's own readers, glTF and
# GLB through Assimp; each input is read and then triangulated, as load_mesh does (fuzz/fuzz_target.h). And
# the scene reader: JSON text -> Scene -> world triangles (fuzz/fuzz_scene.cpp), and the environment image a
# scene names: bytes -> .png/.exr/.hdr file -> make_environment_map (fuzz/fuzz_env_image.cpp).
# usage: scripts/fuzz.sh [SECONDS_PER_TARGET] [TARGET...]      (default: 60 seconds; all targets)
#   targets: off obj ply stl assimp_gltf assimp_glb scene env_image
#   env: VOXR_FUZZ_BUILD (build tree, default build-fuzz), VOXR_FUZZ_PARALLEL (targets at once, default 1),
#        VOXR_FUZZ_JOBS (compile jobs, default 2), VOXR_FUZZ_FLAGS (extra libFuzzer flags)
# Configures a clang build tree with VOXR_BUILD_FUZZERS=ON, builds the targets, seeds each target's working
# corpus (BUILD/corpus/TARGET, kept between runs) from fuzz/corpus/FORMAT, runs each target for the given
# time with -timeout=10 -rss_limit_mb=2048, and prints executions, exec/s, corpus size and findings per
# target. Findings (crash-*, timeout-*, oom-*, leak-* inputs) land in BUILD/findings/TARGET; reproduce one
# with BUILD/fuzz/fuzz_TARGET FILE. Exits 1 when this run found anything.
set -euo pipefail
cd "$(dirname "$0")/.."
seconds=${1:-60}
shift || true
targets=("$@")
[ ${#targets[@]} -gt 0 ] || targets=(off obj ply stl assimp_gltf assimp_glb scene env_image)
build=${VOXR_FUZZ_BUILD:-build-fuzz}
parallel=${VOXR_FUZZ_PARALLEL:-1}

mkdir -p "$build"
CC=${CC:-clang} CXX=${CXX:-clang++} cmake -S . -B "$build" -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DVOXR_BUILD_FUZZERS=ON -DVOXR_BUILD_TESTS=OFF -DVOXR_BUILD_BENCH=OFF -DVOXR_BUILD_VIEWER=OFF \
  -DVOXR_WITH_OPENVDB=OFF > "$build/configure.log" 2>&1 || { cat "$build/configure.log"; exit 1; }
cmake --build "$build" -j"${VOXR_FUZZ_JOBS:-2}" --target "${targets[@]/#/fuzz_}"

seeds_of() {  # seed folder and dictionary of a target
  case $1 in assimp_*) echo "${1#assimp_}" ;; *) echo "$1" ;; esac
}

export ASAN_OPTIONS=${ASAN_OPTIONS:-abort_on_error=1:detect_leaks=1}
export LSAN_OPTIONS=${LSAN_OPTIONS:-suppressions=$PWD/fuzz/lsan.supp:print_suppressions=0}
export UBSAN_OPTIONS=${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1}
run_target() {
  local t=$1 format
  format=$(seeds_of "$t")
  local corpus=$build/corpus/$t findings=$build/findings/$t log=$build/logs/$t.log
  mkdir -p "$corpus" "$findings" "$build/logs"
  cp -n fuzz/corpus/"$format"/* "$corpus"/ 2> /dev/null || true
  # shellcheck disable=SC2086
  "$build/fuzz/fuzz_$t" -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 -print_final_stats=1 \
    -dict=fuzz/dict/"$format".dict -artifact_prefix="$findings/" ${VOXR_FUZZ_FLAGS:-} "$corpus" \
    > "$log" 2>&1 || true
}

touch "$build/run.start"  # findings of this run are newer than this
pids=()
for t in "${targets[@]}"; do
  run_target "$t" &
  pids+=($!)
  if [ ${#pids[@]} -ge "$parallel" ]; then
    wait "${pids[0]}"
    pids=("${pids[@]:1}")
  fi
done
wait

status=0
printf '%-12s %12s %8s %8s %8s  %s\n' target executions exec/s corpus rss_mb findings
for t in "${targets[@]}"; do
  log=$build/logs/$t.log
  stat() { sed -n "s/^stat::$1: *//p" "$log" | tail -1; }
  found=$(find "$build/findings/$t" -type f -newer "$build/run.start" | sort)
  printf '%-12s %12s %8s %8s %8s  %s\n' "$t" "$(stat number_of_executed_units)" \
    "$(stat average_exec_per_sec)" "$(find "$build/corpus/$t" -type f | wc -l)" "$(stat peak_rss_mb)" \
    "$(echo "$found" | grep -c . || true)"
  if [ -n "$found" ]; then
    status=1
    echo "$found" | sed 's/^/    /'
    grep -m1 -E 'ERROR: (AddressSanitizer|libFuzzer|LeakSanitizer)|runtime error|broken promise|deadly signal' \
      "$log" | sed 's/^/    /' || true
  fi
done
exit $status
