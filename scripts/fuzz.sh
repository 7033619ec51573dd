#!/usr/bin/env bash
# Builds the libFuzzer targets (build-fuzz: clang, ASan + UBSan, SYMCOMPRESS_BUILD_FUZZERS) and runs each
# for SECONDS (default 60) on its seeds in fuzz/corpus/<format>/, one after the other. Fails on any crash,
# sanitizer report, leak, input taking more than 10 s, or more than 2 GB of memory; the input that did it
# is left in build-fuzz/findings/<format>/ and the end of the fuzzer's log is printed. Inputs over 2 s are
# listed as slow units there too.
#   scripts/fuzz.sh [SECONDS] [FORMAT...]     FORMAT: glb gltf x3d obj ply stl (default: all)
# FUZZ_JOBS sets the build's parallelism (default: the number of cores).
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$here"
seconds="${1:-60}"
shift || true
formats=("$@")
((${#formats[@]})) || formats=(glb gltf x3d obj ply stl)

CC=clang CXX=clang++ cmake -S . -B build-fuzz -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O2 -g1" \
  -DSYMCOMPRESS_BUILD_FUZZERS=ON -DSYMCOMPRESS_BUILD_TESTS=OFF -DSYMCOMPRESS_BUILD_BENCH=OFF >/dev/null
targets=()
for format in "${formats[@]}"; do targets+=("fuzz_$format"); done
cmake --build build-fuzz -j "${FUZZ_JOBS:-$(nproc)}" --target "${targets[@]}"

failed=()
for format in "${formats[@]}"; do
  # New inputs go to the build folder's corpus; the committed seeds are only read.
  corpus="build-fuzz/corpus/$format" findings="build-fuzz/findings/$format" log="build-fuzz/fuzz_$format.log"
  mkdir -p "$corpus" "$findings"
  if build-fuzz/fuzz/"fuzz_$format" "$corpus" "fuzz/corpus/$format" -dict="fuzz/$format.dict" \
       -max_total_time="$seconds" -timeout=10 -report_slow_units=2 -rss_limit_mb=2048 -artifact_prefix="$findings/" -print_final_stats=1 \
       >"$log" 2>&1; then
    # Coverage from the last status line ("#N DONE cov: C ft: F corp: ..."), and the number of executions.
    coverage=$(sed -n 's/^#[0-9]*[[:space:]]*DONE[[:space:]]*\(cov: [0-9]* ft: [0-9]*\).*/\1/p' "$log" | tail -n 1)
    runs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$log" | tail -n 1)
    echo "fuzz: $format: ok, ${runs:-?} executions in ${seconds} s, ${coverage:-no coverage line}"
  else
    echo "fuzz: $format: FAILED (log: $log; input: $findings/)"
    tail -n 60 "$log"
    failed+=("$format")
  fi
done
if ((${#failed[@]})); then
  echo "fuzz: findings in ${failed[*]}"
  exit 1
fi
echo "fuzz: ${#formats[@]} targets ran ${seconds} s each without a finding"
