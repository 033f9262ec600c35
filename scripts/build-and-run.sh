#!/usr/bin/env bash
# Builds the release configuration and runs the main job: renders the default scene
# (`compress`, 300 frames = 3 s at h = 0.01) offscreen to out/frames/frame_NNNNNN.png.
# No display is needed. A rerun overwrites the frames (--force).
set -euo pipefail
cd "$(dirname "$0")/.."
cmake --preset release >/dev/null
cmake --build --preset release
mkdir -p out
build/release/app/invfree render --scene compress --frames 300 --out out/frames --force
echo "wrote out/frames/frame_000000.png ... frame_000299.png (frame 0: the initial state)"
