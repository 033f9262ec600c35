#!/usr/bin/env bash
# Installs what the web build (docs/web.md) needs on Debian 12, all from Debian's archive:
#   - emscripten 3.1.6 and node-acorn (its JavaScript optimizer's parser);
#   - chromium, chromium-driver, python3-selenium and python3-pil for the tests in a
#     headless browser (python3-pil compares the screenshot with its golden);
#   - Dear ImGui's sources (Debian's source package `imgui`, 1.86, the version of
#     libimgui-dev, which ships headers and an x86 library only): unpacked with
#     `apt-get source` into build/web-deps/ (outside git; nothing is copied into the
#     repository). pugixml's sources the same way (Debian's source package `pugixml`, the
#     version of libpugixml-dev, one .cpp) into build/web-deps/pugixml: the page reads the
#     built-in scenes' SVG outlines with the desktop's code. A deb-src entry for bookworm is added when apt has none, made from the
#     machine's own bookworm `deb` entry (same mirror, same signing key).
# Run as root or through sudo (the unpacking runs as the calling user). Idempotent.
set -euo pipefail
cd "$(dirname "$0")/.."
SUDO=""
[ "$(id -u)" -eq 0 ] || SUDO="sudo"

packages=(emscripten node-acorn dpkg-dev chromium chromium-driver python3-selenium python3-pil)
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  echo "install-web-deps: installing ${missing[*]}"
  $SUDO apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
fi

# deb-src for bookworm: copy the deb822 stanza (or one-line entry) that serves bookworm's
# binary packages, as a source entry.
if ! apt-cache showsrc imgui 2>/dev/null | grep -q '^Package: imgui' ||
  ! apt-cache showsrc pugixml 2>/dev/null | grep -q '^Package: pugixml'; then
  src=/etc/apt/sources.list.d/invfree-deb-src.sources
  entry=""
  for f in /etc/apt/sources.list.d/*.sources; do
    [ -f "$f" ] || continue
    entry=$(awk 'BEGIN { RS = ""; FS = "\n" }
      {
        types = ""; suites = ""; out = ""
        for (i = 1; i <= NF; i++) {
          if ($i ~ /^#/) continue
          if ($i ~ /^Types:/) { types = $i; continue }
          if ($i ~ /^Suites:/) { suites = $i; continue }
          out = out $i "\n"
        }
        if (types ~ /[ \t]deb([ \t]|$)/ && suites ~ /[ \t]bookworm([ \t]|$)/) {
          printf "Types: deb-src\nSuites: bookworm\n%s", out
          exit
        }
      }' "$f")
    [ -n "$entry" ] && break
  done
  if [ -n "$entry" ]; then
    echo "install-web-deps: adding $src (deb-src for bookworm)"
    printf '# Added by invfree scripts/install-web-deps.sh: Dear ImGui sources for the web build.\n%s\n' \
      "$entry" | $SUDO tee "$src" >/dev/null
  else
    line=$(grep -hE '^deb[[:space:]]+[^[:space:]]+[[:space:]]+bookworm[[:space:]]' \
      /etc/apt/sources.list /etc/apt/sources.list.d/*.list 2>/dev/null | head -n 1 || true)
    if [ -z "$line" ]; then
      echo "install-web-deps: no bookworm entry in apt's sources to derive a deb-src entry from;" \
        "add one (Types: deb-src, Suites: bookworm) and run this again" >&2
      exit 1
    fi
    src=/etc/apt/sources.list.d/invfree-deb-src.list
    echo "install-web-deps: adding $src (deb-src for bookworm)"
    echo "deb-src${line#deb}" | $SUDO tee "$src" >/dev/null
  fi
  $SUDO apt-get update -qq
fi

# Sources the page compiles itself (Debian's patches applied), unpacked once into
# build/web-deps/NAME: the source package of the -dev package the desktop build uses (same
# headers, same version when that is installed).
deps=build/web-deps
unpack_source() {  # NAME (source package and folder), DEV_PACKAGE, a file the tree must have
  local name=$1 dev=$2 check=$3
  [ -f "$deps/$name/$check" ] && return 0
  mkdir -p "$deps"
  rm -rf "$deps/unpack"
  mkdir "$deps/unpack"
  local version
  version=$(dpkg-query -W -f='${source:Version}' "$dev" 2>/dev/null || true)
  (cd "$deps/unpack" && apt-get source -qq "$name${version:+=$version}")
  local dir
  dir=$(find "$deps/unpack" -mindepth 1 -maxdepth 1 -type d -name "$name-*" | head -n 1)
  [ -f "$dir/$check" ] || { echo "install-web-deps: apt-get source $name gave no $check" >&2; exit 1; }
  rm -rf "$deps/$name"
  mv "$dir" "$deps/$name"
  rm -rf "$deps/unpack"
}
unpack_source imgui libimgui-dev imgui.cpp
unpack_source pugixml libpugixml-dev src/pugixml.cpp
echo "install-web-deps: emscripten $(dpkg-query -W -f='${Version}' emscripten), Dear ImGui sources in $deps/imgui, pugixml sources in $deps/pugixml"
