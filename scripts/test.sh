#!/usr/bin/env bash
# Installs what is missing, builds (Release, then AddressSanitizer + UndefinedBehaviorSanitizer) and
# runs every test through CTest in both builds, then every fuzz target for a minute (scripts/fuzz.sh).
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$here"
# Each phase's wall time, printed as it ends, so that CI's budget can be watched.
started=$SECONDS
phase() { echo "test.sh: $1 took $((SECONDS - started)) s"; started=$SECONDS; }
scripts/install-deps.sh
phase "installing what is missing"
jobs=$(nproc)

cmake -S . -B build -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build build -j "$jobs"
phase "the Release build"
(cd build && ctest --output-on-failure -j "$jobs")
phase "the Release tests"

# The sanitizer build skips the benchmarks, the slow interoperability checks run above, and the largest
# models (SYMCOMPRESS_QUICK). Clang (which the fuzzers need anyway) builds it in some 7 minutes where GCC
# took 15 to 20, and -O1 with line tables in half the time of -O2 -g; the stack traces keep their file:line.
cmake -S . -B build-asan -DCMAKE_CXX_COMPILER=clang++ -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -g1 -DNDEBUG" -DSYMCOMPRESS_SANITIZE=ON -DSYMCOMPRESS_BUILD_BENCH=OFF >/dev/null
cmake --build build-asan -j "$jobs"
phase "the sanitizer build"
(cd build-asan && ASAN_OPTIONS=detect_leaks=1 UBSAN_OPTIONS=print_stacktrace=1 SYMCOMPRESS_SKIP_INTEROP=1 SYMCOMPRESS_QUICK=1 \
   ctest --output-on-failure -j "$jobs")
phase "the sanitizer tests"

# The readers under libFuzzer (clang, ASan + UBSan), 60 s per format: about 8 minutes with the build.
scripts/fuzz.sh 60
phase "the fuzzers"
