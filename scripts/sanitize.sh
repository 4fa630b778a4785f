#!/usr/bin/env bash
# The sanitizer job: builds the test suite with clang++ under AddressSanitizer and
# UndefinedBehaviorSanitizer (including float-cast-overflow, which GCC's
# -fsanitize=undefined leaves out) in build-sanitize/, then runs ctest so that any
# report fails the run (halt_on_error=1, no recovery).
#
#   bash scripts/sanitize.sh            # the whole suite (the thorough part)
#   bash scripts/sanitize.sh fast       # core and output tests only (what CI runs when short of time)
#
# Needs clang (Debian package clang); it is installed when missing and the script runs as root.
# Suppressions for the uninstrumented Debian libraries (Embree, TBB) are in scripts/sanitizers/.
set -euo pipefail
cd "$(dirname "$0")/.."
part="${1:-all}"
root="$(pwd)"

if ! command -v clang++ > /dev/null; then
  if [ "$(id -u)" -ne 0 ]; then echo "sanitize: clang++ missing (apt-get install clang)" >&2; exit 1; fi
  apt-get update -qq && DEBIAN_FRONTEND=noninteractive apt-get install -y -qq clang > /dev/null
fi

export ASAN_OPTIONS="halt_on_error=1:abort_on_error=0:detect_leaks=1:detect_stack_use_after_return=0:suppressions=${root}/scripts/sanitizers/asan.supp"
export LSAN_OPTIONS="suppressions=${root}/scripts/sanitizers/lsan.supp:print_suppressions=0"
export UBSAN_OPTIONS="halt_on_error=1:print_stacktrace=1:suppressions=${root}/scripts/sanitizers/ubsan.supp"

# pointer-overflow alone recovers, so that scripts/sanitizers/ubsan.supp can drop Eigen's null + offset
# (suppressions need a recoverable check); halt_on_error=1 still stops at any other report.
flags="-O1 -g -fno-omit-frame-pointer -fsanitize=address,undefined,float-cast-overflow -fno-sanitize-recover=all -fsanitize-recover=pointer-overflow"
launcher=()
command -v ccache > /dev/null && launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache -DCMAKE_C_COMPILER_LAUNCHER=ccache)
cmake -S . -B build-sanitize -DCMAKE_BUILD_TYPE=Debug -DBUILD_TESTING=ON -DILP_BUILD_BENCHMARKS=OFF \
      -DCMAKE_CXX_COMPILER=clang++ -DCMAKE_CXX_FLAGS="$flags" -DCMAKE_CXX_FLAGS_DEBUG="" \
      -DCMAKE_EXE_LINKER_FLAGS="-fsanitize=address,undefined,float-cast-overflow" "${launcher[@]}" > /dev/null

jobs="$(nproc)"
start=$(date +%s)
case "$part" in
  fast)
    cmake --build build-sanitize -j"$jobs" --target core_tests output_tests
    # The ctest names of those two programs' tests: "^(Suite|...)[./]".
    suites=$(for t in build-sanitize/tests/core/core_tests build-sanitize/tests/output/output_tests; do
               "$t" --gtest_list_tests | grep -v '^ ' | sed 's/\.$//; s/^.*\///'; done | sort -u | paste -sd '|')
    ctest --test-dir build-sanitize --output-on-failure -j"$jobs" -R "^([A-Za-z0-9_]+/)?(${suites})[./]" ;;
  all)
    cmake --build build-sanitize -j"$jobs"
    ctest --test-dir build-sanitize --output-on-failure -j"$jobs" ;;
  *) echo "usage: scripts/sanitize.sh [all|fast]" >&2; exit 2 ;;
esac
echo "sanitize ($part): passed in $(( $(date +%s) - start )) s"
