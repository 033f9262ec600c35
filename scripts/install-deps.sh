#!/usr/bin/env bash
# Installs the Debian 12 packages invfree needs (only those missing). As root it calls
# apt-get directly (a fresh Debian root shell has no sudo); as any other user through sudo.
# scripts/build-and-run.sh and scripts/build-and-test.sh run it first. Everything comes
# from Debian's archive; nothing is downloaded at build time.
set -euo pipefail
packages=(
  build-essential cmake pkg-config git
  libeigen3-dev libtomlplusplus-dev libcli11-dev          # core, scenes, command line
  libpugixml-dev                                          # SVG shape files (XML)
  libcgal-dev                                             # meshing shapes (CGAL, GPL: see LICENSE)
  libspectra-dev                                          # sparse eigenpairs (modal basis, modes)
  libgtest-dev libbenchmark-dev                           # tests, benchmarks
  libsuitesparse-dev libopenblas0-pthread                 # CHOLMOD direct solver
  libosmesa6-dev libglfw3-dev libimgui-dev libstb-dev     # offscreen and live rendering
  zlib1g-dev                                              # PNG frames (deflate for stb_image_write)
  libcairo2-dev libfreetype-dev fonts-dejavu-core         # charts (PNG, SVG, PDF) and their text
  xvfb xauth                                              # live-mode tests without a display
  clang libclang-rt-14-dev                                # libFuzzer target
  ffmpeg                                                  # optional: render --mp4
  ccache                                                  # compile cache (rebuilds, CI)
  pybind11-dev python3-numpy python3-pytest python3-matplotlib  # the Python module (docs/python.md)
)
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -eq 0 ]; then
  echo "install-deps: all ${#packages[@]} packages present"
  exit 0
fi
SUDO=""
if [ "$(id -u)" -ne 0 ]; then
  if ! command -v sudo >/dev/null; then
    echo "install-deps: missing ${missing[*]}; run as root or install sudo" >&2
    exit 1
  fi
  SUDO="sudo"
fi
echo "install-deps: installing ${missing[*]}"
$SUDO apt-get update -qq
$SUDO env DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends "${missing[@]}"
