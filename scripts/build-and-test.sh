#!/usr/bin/env bash
# Builds the release configuration and runs the whole test suite.
set -euo pipefail
cd "$(dirname "$0")/.."
cmake --preset release >/dev/null
cmake --build --preset release
ctest --preset release
