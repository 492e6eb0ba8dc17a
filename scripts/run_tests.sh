#!/bin/bash
# The whole test suite, as CI runs it (README's second command, .ci/run):
#   1. Release build of everything in build/, and its CTest suite;
#   2. the same test suite built with AddressSanitizer and
#      UndefinedBehaviorSanitizer (-DHMO_SANITIZE=ON) in build-asan/: any
#      report fails the test that caused it;
#   3. the libFuzzer targets of every reader (clang++, ASan + UBSan) in
#      build-fuzz/, each run for FUZZ_SECONDS (default 60) on its seed
#      corpus and regression inputs (scripts/fuzz.sh).
# About an hour on 2 cores from scratch (71 min measured from a fresh clone of
# the commit that added the Python, examples and manual tests, with other
# builds sharing the 2 cores; 43.7 min before them).
set -euo pipefail
cd "$(dirname "$0")/.."
jobs="$(nproc)"

echo "== Release build and tests (build/)"
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release -DBUILD_TESTING=ON
cmake --build build -j"$jobs"
ctest --test-dir build --output-on-failure --no-tests=error

echo "== ASan + UBSan build and tests (build-asan/)"
cmake -S . -B build-asan -DCMAKE_BUILD_TYPE=Release -DBUILD_TESTING=ON -DHMO_SANITIZE=ON
cmake --build build-asan -j"$jobs"
ctest --test-dir build-asan --output-on-failure --no-tests=error

echo "== fuzzing the readers (build-fuzz/)"
bash scripts/fuzz.sh "${FUZZ_SECONDS:-60}"
