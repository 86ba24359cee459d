#!/bin/sh
# The main job: set up what is missing, build, run the headless Box2D demo (rough curved bodies with
# ordinary boxes and circles in a Box2D 2.4 world). Results and pictures go to out/demo/.
set -eu
cd "$(dirname "$0")/.."
sh scripts/setup.sh
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release -DRUGO_BUILD_TESTS=OFF >/dev/null
cmake --build build -j "$(nproc 2>/dev/null || echo 2)"
./build/samples/box2d/b2_demo out/demo
