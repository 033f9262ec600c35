#!/usr/bin/env bash
# Installs what is missing, builds invfree and runs the whole test suite, as CI does
# (.ci/run calls this script):
#   0. scripts/install-deps.sh (as root directly, otherwise through sudo)
#   1. release build, every test (ctest), the heavy ones included
#   2. libFuzzer over the scene parser and --set overrides for INVFREE_FUZZ_SECONDS (60)
#   3. AddressSanitizer + UndefinedBehaviorSanitizer build (preset "sanitize": -O1, assertions
#      on, -g1: line tables for the reports' stack traces, a third less compile time than -g)
#      of the test executables without GL (label `core`: the core, the scene reader, the
#      command line, reliability, fuzz replay; tests/CMakeLists.txt) and the Python module
#      (its API tests under ASan, tests/python/CMakeLists.txt), and those tests but the
#      heavy ones. The GL code (render, live, charts) and its tests run in release.
#   4. where the web toolchain is installed (emcc, chromium and selenium, from
#      scripts/install-web-deps.sh), the web page: scripts/install-web-deps.sh (fetches Dear
#      ImGui's and pugixml's sources if missing), scripts/build-web.sh and its test in headless Chromium
#      (ctest -L web; docs/web.md): about 6 minutes on 2 cores. Elsewhere the web test
#      reports itself skipped, saying why.
# INVFREE_CI_STAGES picks stages (default "release,fuzz,sanitize", and "web" where its
# toolchain is installed), e.g.
#   INVFREE_CI_STAGES=release bash scripts/build-and-test.sh    # the quick local check
#   INVFREE_CI_STAGES=release,web bash scripts/build-and-test.sh  # + the page in a browser
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
default_stages="release,fuzz,sanitize"
if command -v emcc >/dev/null && command -v chromium >/dev/null &&
   /usr/bin/python3 -c 'import selenium' 2>/dev/null; then
  default_stages+=",web"
fi
stages=",${INVFREE_CI_STAGES:-$default_stages},"
# Each stage's time, printed as it ends and in a summary at the end. Compiles go through
# ccache (CMakeLists.txt), so a machine that built before rebuilds in a fraction of the time.
start=$SECONDS
stage_name="" stage_start=$SECONDS summary=""
stage() {
  if [[ -n $stage_name ]]; then
    echo "=== $stage_name: $((SECONDS - stage_start)) s"
    summary+="$(printf '%6d s  %s' $((SECONDS - stage_start)) "$stage_name")"$'\n'
  fi
  stage_name=$1 stage_start=$SECONDS
  [[ -n $1 ]] && echo "=== $1 (at $((SECONDS - start)) s)"
  return 0
}

if [[ $stages == *,release,* ]]; then
  stage "release: build and test"
  cmake --preset release >/dev/null
  cmake --build --preset release
  ctest --preset release
fi
if [[ $stages == *,fuzz,* ]]; then
  stage "fuzz"
  bash scripts/fuzz.sh "${INVFREE_FUZZ_SECONDS:-60}"
fi
if [[ $stages == *,sanitize,* ]]; then
  stage "AddressSanitizer + UBSan: build and test"
  cmake --preset sanitize >/dev/null
  cmake --build --preset sanitize --target invfree_tests invfree_reliability_tests invfree_shape_tests \
    invfree_scene_fuzz_replay invfree_python
  ASAN_OPTIONS=abort_on_error=1:detect_leaks=1:strict_string_checks=1 \
  UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 \
  LSAN_OPTIONS="suppressions=$PWD/tests/lsan.supp:print_suppressions=0" \
    ctest --preset sanitize --label-regex core --label-exclude heavy
fi
if [[ $stages == *,web,* ]]; then
  stage "web page: build and test in headless Chromium"
  bash scripts/install-web-deps.sh  # uses sudo itself where it needs root
  bash scripts/build-web.sh
  cmake --preset release >/dev/null
  ctest --preset release -L web
fi
stage ""
echo "=== stage times"
printf '%s' "$summary"
echo "=== done in $((SECONDS - start)) s"
