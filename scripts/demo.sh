#!/usr/bin/env bash
# The main job from a fresh Debian 12 machine: dependencies, a Release build, then the sample
# Cornell box converted, its k-d tree built and rendered to out/cornell-box.png.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release -DKDRAY_BUILD_TESTS=OFF
cmake --build build -j"$(nproc)"
make -C samples BUILD="$PWD/build" OUT="$PWD/out" demo
