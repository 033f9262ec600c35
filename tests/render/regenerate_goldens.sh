#!/usr/bin/env bash
# Regenerates the screenshot goldens (tests/render/goldens/*.png) from the current
# renderer: builds the render tests in the release configuration and runs the golden
# cases with INVFREE_UPDATE_GOLDENS=1, which writes each golden instead of comparing.
# That is every RenderGolden case: det F's and the other colourings' (psi, stress,
# clamped), the stress glyphs and the selected triangle. Look at every changed PNG before
# committing it (git diff --stat tests/render/goldens).
set -euo pipefail
cd "$(dirname "$0")/../.."
cmake --preset release >/dev/null
cmake --build --preset release --target invfree_render_tests
env -u DISPLAY INVFREE_UPDATE_GOLDENS=1 build/release/tests/render/invfree_render_tests \
  --gtest_filter='RenderGolden.*:RenderCli.WritesFramesAndFrameZeroIsTheInitialState'
echo "regenerated: $(ls tests/render/goldens/*.png | tr '\n' ' ')"
