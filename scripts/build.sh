#!/usr/bin/env bash
# Install what is missing (Debian packages, packaged meshes), configure and build voxr in Release.
# usage: scripts/build.sh [BUILD_DIR]   (default: build)
set -euo pipefail
cd "$(dirname "$0")/.."
build=${1:-build}
./scripts/install-deps.sh
./scripts/fetch-meshes.sh
cmake -S . -B "$build" -DCMAKE_BUILD_TYPE=Release > /dev/null
cmake --build "$build" -j"$(nproc)"
