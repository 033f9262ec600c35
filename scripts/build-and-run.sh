#!/usr/bin/env bash
# The main job on a fresh Debian 12 machine: installs the packages that are missing
# (scripts/install-deps.sh: as root directly, otherwise through sudo), builds the program
# alone (`invfree` in the release configuration, not the tests) and renders the default
# scene (`compress`, 300 frames = 3 s at h = 0.01) offscreen to
# out/frames/frame_NNNNNN.png. No display is needed. A rerun overwrites the frames (--force).
#   bash scripts/build-and-run.sh
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
cmake --preset release >/dev/null
cmake --build --preset release --target invfree
mkdir -p out
build/release/app/invfree render --scene compress --frames 300 --out out/frames --force
echo "wrote out/frames/frame_000000.png ... frame_000299.png (frame 0: the initial state)"
