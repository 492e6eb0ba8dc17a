#!/bin/bash
# Builds the libFuzzer targets of the readers (clang++, ASan + UBSan) in
# build-fuzz/ and runs each for SECONDS as CTest tests, as many at a time as
# there are cores. The test suite runs them for 30 s each; before a release,
# run them for 10 minutes each: scripts/fuzz.sh 600.
# usage: scripts/fuzz.sh [SECONDS]     (default 30)
#        scripts/fuzz.sh --build-only
# (needs the packages clang, libclang-rt-14-dev)
set -euo pipefail
cd "$(dirname "$0")/.."
if [ "${1:-}" = "--build-only" ]; then
  cmake -S . -B build-fuzz -DCMAKE_CXX_COMPILER=clang++ -DCMAKE_BUILD_TYPE=Release -DHMO_FUZZ=ON > /dev/null
  cmake --build build-fuzz -j"$(nproc)"
  exit 0
fi
seconds="${1:-30}"
cmake -S . -B build-fuzz -DCMAKE_CXX_COMPILER=clang++ -DCMAKE_BUILD_TYPE=Release -DHMO_FUZZ=ON \
      -DHMO_FUZZ_SECONDS="$seconds" > /dev/null
cmake --build build-fuzz -j"$(nproc)"
ctest --test-dir build-fuzz --output-on-failure --no-tests=error -j"$(nproc)" -V |
  grep -E -- "-- fuzz_read_|problem|tests passed|Failed|Passed"
