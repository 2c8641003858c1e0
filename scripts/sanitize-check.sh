#!/usr/bin/env bash
# Build voxr, voxr_core, voxr_io and voxr_tests in Debug with AddressSanitizer and UndefinedBehaviorSanitizer
# (CMake option VOXR_SANITIZE) in a tree of their own, then run the test suite there (what CI runs after the
# Release suite: .ci/run).
#
# Debug also means launch checks: without NDEBUG, ClRuntime::enqueue (host/cl/cl_runtime.cpp, the one place
# every kernel is enqueued) finishes the queue and resolves the launch's profiling event after each kernel,
# so an asynchronous failure is thrown as a voxr::Error naming that kernel instead of surfacing later.
#
# usage: scripts/sanitize-check.sh [BUILD_DIR]   (default: build-asan)
set -euo pipefail
cd "$(dirname "$0")/.."
build=${1:-build-asan}
./scripts/install-deps.sh
./scripts/fetch-meshes.sh

# Every finding is fatal (ASan and LSan by default, UBSan through -fno-sanitize-recover) and fails the test
# that hit it, with a stack.
# - Leaks stay on. scripts/lsan.supp names the two libraries whose process-lifetime state is never freed:
#   the OpenCL driver PoCL and the LLVM it JIT-compiles kernels with (one 16-byte block in libpocl roots a
#   tree of LLVM pass-manager objects); voxr's own allocations are still checked.
# - use_sigaltstack=0: LLVM (inside PoCL) installs its own alternate signal stack, malloc'ed, on the threads
#   that compile kernels; ASan then tries to munmap it as its own when the thread exits and aborts the
#   process ("failed to deallocate ... UnsetAlternateSignalStack"). The only cost: a stack overflow is
#   reported as a plain SEGV.
# - check_initialization_order, strict_string_checks: cheap extra checks, off by default.
export ASAN_OPTIONS="detect_leaks=1:use_sigaltstack=0:check_initialization_order=1:strict_string_checks=1${ASAN_OPTIONS:+:$ASAN_OPTIONS}"
# print_suppressions=0: otherwise LSan appends a "Suppressions used" table to stderr whenever one matched,
# which the CLI tests read (they expect exactly the one-line error voxr prints).
export LSAN_OPTIONS="suppressions=$PWD/scripts/lsan.supp:print_suppressions=0${LSAN_OPTIONS:+:$LSAN_OPTIONS}"
export UBSAN_OPTIONS="print_stacktrace=1${UBSAN_OPTIONS:+:$UBSAN_OPTIONS}"

# -O1: the property tests over rotated meshes take minutes unoptimised under ASan; -O1 keeps the stacks
# readable and, without NDEBUG, the launch checks. -g1: line tables only, all a sanitizer's stack needs
# (function, file, line); full debug info cost 14 % more compile time (polygon_triangulation.cpp: 28.7 s vs
# 24.6 s of CPU), and CI's time goes mostly to compiling.
cmake -S . -B "$build" -DCMAKE_BUILD_TYPE=Debug -DCMAKE_CXX_FLAGS_DEBUG="-g1 -O1" -DVOXR_SANITIZE=ON -DVOXR_BUILD_BENCH=OFF \
  -DVOXR_WITH_OPENVDB=OFF -DVOXR_BUILD_VIEWER=OFF > /dev/null
cmake --build "$build" -j"$(nproc)" --target voxr voxr_core voxr_io voxr_tests
# --repeat until-pass:2: LeakSanitizer's own tracer has crashed at exit once in three full runs while PoCL's
# threads were being stopped ("Tracer caught signal 11 ... LeakSanitizer has encountered a fatal error", after
# the test itself passed); a test that fails twice is a finding.
# The kernels are the same sources with the same options as in the Release tree: when its PoCL cache exists
# (CI runs the Release suite first), the sanitized tests reuse its compiled kernels instead of compiling every
# program again (PoCL keys its cache by source, options and device, so a stale entry cannot be picked up).
if [ -z "${POCL_CACHE_DIR:-}" ] && [ -d build/pocl-cache ]; then export POCL_CACHE_DIR="$PWD/build/pocl-cache"; fi
cd "$build" && ctest --output-on-failure -j2 --timeout 900 --repeat until-pass:2
