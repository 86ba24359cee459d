#!/bin/sh
# The main job: set up what is missing, build, run the headless demo. Results go to out/demo/.
set -eu
cd "$(dirname "$0")/.."
sh scripts/setup.sh
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release -DRUGO_BUILD_TESTS=OFF >/dev/null
cmake --build build -j "$(nproc 2>/dev/null || echo 2)"
./build/samples/rugo_demo out/demo
