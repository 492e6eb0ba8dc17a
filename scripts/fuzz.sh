#!/bin/bash
# Builds the libFuzzer targets of the readers (clang++, ASan + UBSan) in
# build-fuzz/ and runs each for SECONDS (default 60) as CTest tests.
# usage: scripts/fuzz.sh [SECONDS]     (needs the packages clang, libclang-rt-14-dev)
set -euo pipefail
cd "$(dirname "$0")/.."
seconds="${1:-60}"
cmake -S . -B build-fuzz -DCMAKE_CXX_COMPILER=clang++ -DCMAKE_BUILD_TYPE=Release -DHMO_FUZZ=ON \
      -DHMO_FUZZ_SECONDS="$seconds" > /dev/null
cmake --build build-fuzz -j"$(nproc)"
ctest --test-dir build-fuzz --output-on-failure --no-tests=error -V | grep -E "fuzz_read_.*(seeds|problem)|tests passed|Failed|Passed"
