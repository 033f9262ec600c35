#!/usr/bin/env bash
# Builds the web page (docs/web.md) into build/web: index.html, index.js, index.wasm.
# Needs the toolchain from scripts/install-web-deps.sh. Serve it with
#   python3 -m http.server -d build/web 8000     (then open http://localhost:8000)
set -euo pipefail
cd "$(dirname "$0")/.."
if ! command -v emcc >/dev/null || [ ! -f build/web-deps/imgui/imgui.cpp ] ||
  [ ! -f build/web-deps/pugixml/src/pugixml.cpp ]; then
  echo "build-web: the web toolchain is missing (run: bash scripts/install-web-deps.sh)" >&2
  exit 1
fi
cmake --preset web >/dev/null
cmake --build --preset web
echo "build-web: the page is in build/web (serve: python3 -m http.server -d build/web 8000)"
