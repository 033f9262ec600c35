#!/usr/bin/env bash
# Builds the release configuration and runs the main job on the default scene.
set -euo pipefail
cd "$(dirname "$0")/.."
cmake --preset release >/dev/null
cmake --build --preset release
mkdir -p out
build/release/app/invfree simulate --scene compress --steps 300 --csv out/compress.csv --obj out/compress_obj
echo "wrote out/compress.csv and out/compress_obj/*.obj"
