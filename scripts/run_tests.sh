#!/bin/bash
# The whole test suite, as CI runs it (README's second command, .ci/run):
#   install   the Debian packages that are missing (install_dependencies.sh --tests);
#   Release   build/: everything, and its CTest suite (the C++ tests, the
#             command-line test, the examples, Python, the meshio/gmsh
#             cross-checks, the benchmark's stress sample), tests run in parallel;
#   manual    the manual with its figures, 0 doxygen warnings (CTest label "manual");
#   ASan      build-asan/: the C++ tests and the tool built with AddressSanitizer
#             and UndefinedBehaviorSanitizer (-DHMO_SANITIZE=ON), at -O1 and on
#             inputs sized for them (the large meshes run in the Release phase);
#   fuzz      build-fuzz/: one libFuzzer target per reader, each run for
#             FUZZ_SECONDS (default 30; scripts/fuzz.sh 600 before a release).
# It ends with a table of the phases and their wall times. A failed phase
# stops the run; the table then says which.
set -uo pipefail
cd "$(dirname "$0")/.."
jobs="$(nproc)"
fuzz_seconds="${FUZZ_SECONDS:-30}"
# a hang guard, not a time bound: no test comes near it
ctest_args=(--output-on-failure --no-tests=error --timeout 1800 -j"$jobs")

phase_names=()
phase_seconds=()
phase_status=()
run_start=$(date +%s%N)

print_table()
{
  local total
  total=$(( ($(date +%s%N) - run_start) / 1000000 ))
  echo
  echo "| phase | wall time | status |"
  echo "|---|---:|---|"
  for i in "${!phase_names[@]}"; do
    printf "| %s | %s | %s |\n" "${phase_names[$i]}" "$(format_seconds "${phase_seconds[$i]}")" "${phase_status[$i]}"
  done
  printf "| **total** | **%s** | |\n" "$(format_seconds "$total")"
}

format_seconds() # milliseconds 754321 -> "754 s (12.6 min)" (bash arithmetic: no bc on a bare machine)
{
  local tenths=$(( ($1 + 3000) / 6000 ))
  printf "%d s (%d.%d min)" $(( ($1 + 500) / 1000 )) $(( tenths / 10 )) $(( tenths % 10 ))
}

# phase NAME COMMAND...: runs COMMAND, records its wall time; a failure ends the run
phase()
{
  local name="$1"
  shift
  echo
  echo "== $name"
  local start status
  start=$(date +%s%N)
  "$@"
  status=$?
  phase_names+=("$name")
  phase_seconds+=($(( ($(date +%s%N) - start) / 1000000 )))
  if [ $status -eq 0 ]; then
    phase_status+=("passed")
  else
    phase_status+=("FAILED (exit $status)")
    print_table
    exit $status
  fi
}

phase "install" bash scripts/install_dependencies.sh --tests
phase "Release: configure and build" \
  bash -c "cmake -S . -B build -DCMAKE_BUILD_TYPE=Release -DBUILD_TESTING=ON && cmake --build build -j$jobs"
phase "Release: tests" ctest --test-dir build "${ctest_args[@]}" -LE manual
phase "manual" ctest --test-dir build "${ctest_args[@]}" -L manual
phase "ASan + UBSan: configure and build" \
  bash -c "cmake -S . -B build-asan -DCMAKE_BUILD_TYPE=Release -DBUILD_TESTING=ON -DHMO_SANITIZE=ON && cmake --build build-asan -j$jobs"
phase "ASan + UBSan: tests" ctest --test-dir build-asan "${ctest_args[@]}"
phase "fuzz: build" bash scripts/fuzz.sh --build-only
phase "fuzz: ${fuzz_seconds} s per reader" bash scripts/fuzz.sh "$fuzz_seconds"
print_table
