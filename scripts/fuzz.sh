#!/usr/bin/env bash
# Fuzzes the scene parser and the --set overrides (tests/fuzz/scene_fuzz.cpp) with
# libFuzzer for SECONDS (default 60). Builds the target with clang, AddressSanitizer and
# UndefinedBehaviorSanitizer in $INVFREE_FUZZ_BUILD (default build/fuzz), toml++ in
# header-only mode so the parser itself is instrumented. Starts from the seed corpus
# (assets/scenes/ and tests/fuzz/corpus/); what it learns stays in BUILD/corpus between
# runs. On a finding it prints the input's path: copy it to tests/fuzz/corpus/ as
# regression_<what>.toml (the replay test then keeps it), fix the cause, run again.
#   scripts/fuzz.sh 600      # ten minutes
set -euo pipefail
cd "$(dirname "$0")/.."
seconds=${1:-60}
build=${INVFREE_FUZZ_BUILD:-build/fuzz}
cmake -S . -B "$build" -DCMAKE_CXX_COMPILER=clang++ -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DINVFREE_FUZZ=ON -DINVFREE_BUILD_BENCHMARKS=OFF \
  -DCMAKE_CXX_FLAGS="-fsanitize=fuzzer-no-link,address,undefined -fno-omit-frame-pointer -fno-sanitize-recover=undefined" \
  >/dev/null
cmake --build "$build" --parallel 2 --target invfree_scene_fuzz
mkdir -p "$build/corpus" "$build/artifacts"
echo "fuzz: ${seconds} s over the scene parser and --set overrides"
set +e
"$build/tests/fuzz/invfree_scene_fuzz" -max_total_time="$seconds" -dict=tests/fuzz/scene.dict \
  -timeout=10 -rss_limit_mb=4096 -artifact_prefix="$build/artifacts/" -print_final_stats=1 \
  "$build/corpus" assets/scenes tests/fuzz/corpus >"$build/fuzz.log" 2>&1
status=$?
set -e
grep -E "INITED|^Done|stat::number_of_executed_units|stat::peak_rss_mb" "$build/fuzz.log" || true
if [ "$status" -ne 0 ]; then
  tail -n 60 "$build/fuzz.log"
  echo "fuzz: FAILED (exit $status); the input is in $build/artifacts/:" >&2
  ls -1 "$build/artifacts/" >&2
  exit 1
fi
echo "fuzz: no finding"
