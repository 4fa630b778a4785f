#!/usr/bin/env bash
# Builds every libFuzzer harness fuzz/NAME_fuzz.cpp with clang++ (ASan + UBSan with
# float-cast-overflow, the core library instrumented for coverage) in build-fuzz/,
# then runs each for SECONDS (default 60) on a copy of its seed corpus
# fuzz/corpus/NAME/ (and fuzz/NAME.dict when there is one). A crash, a sanitizer
# report, a leak, a timeout or more than 2 GB of memory fails the script; the input
# that did it is kept in build-fuzz/findings/NAME/.
#
#   bash scripts/fuzz.sh            # 60 s each (what CI can run)
#   bash scripts/fuzz.sh 600        # the longer run of docs/reliability.md
#   bash scripts/fuzz.sh 60 config  # one harness
#   FUZZ_PARALLEL=1 bash scripts/fuzz.sh 600 config,products_grids   # some, at once
#   FUZZ_PARALLEL=1 bash scripts/fuzz.sh 600   # every harness at once
#
# Needs clang (Debian package clang), installed when missing and the script runs as
# root; it is not a requirement of the main build.
set -euo pipefail
cd "$(dirname "$0")/.."
seconds="${1:-60}"
only="${2:-}"

if ! command -v clang++ > /dev/null; then
  if [ "$(id -u)" -ne 0 ]; then echo "fuzz: clang++ missing (apt-get install clang)" >&2; exit 1; fi
  apt-get update -qq && DEBIAN_FRONTEND=noninteractive apt-get install -y -qq clang > /dev/null
fi

flags="-O1 -g -fno-omit-frame-pointer -fsanitize=fuzzer-no-link,address,undefined,float-cast-overflow -fno-sanitize-recover=all"
launcher=()
command -v ccache > /dev/null && launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache -DCMAKE_C_COMPILER_LAUNCHER=ccache)
cmake -S . -B build-fuzz -DCMAKE_BUILD_TYPE=Debug -DBUILD_TESTING=OFF -DILP_BUILD_BENCHMARKS=OFF -DILP_FUZZ=ON \
      -DCMAKE_CXX_COMPILER=clang++ -DCMAKE_CXX_FLAGS="$flags" -DCMAKE_CXX_FLAGS_DEBUG="" \
      -DCMAKE_EXE_LINKER_FLAGS="-fsanitize=address,undefined,float-cast-overflow" "${launcher[@]}" > /dev/null

harnesses=()
for source in fuzz/*_fuzz.cpp; do
  name="$(basename "$source" .cpp)"
  if [ -n "$only" ]; then  # one name, or several separated by commas
    case ",$only," in *",${name%_fuzz},"* | *",$name,"*) ;; *) continue ;; esac
  fi
  harnesses+=("$name")
done
[ ${#harnesses[@]} -gt 0 ] || { echo "fuzz: no harness fuzz/*_fuzz.cpp${only:+ named $only}" >&2; exit 1; }
cmake --build build-fuzz -j"$(nproc)" --target "${harnesses[@]}"

export ASAN_OPTIONS="halt_on_error=1:detect_leaks=1:allocator_may_return_null=1"
# Leaks inside uninstrumented Debian libraries that are not ours, as the sanitizer job has them.
export LSAN_OPTIONS="suppressions=$(pwd)/scripts/sanitizers/lsan.supp:print_suppressions=0"
export UBSAN_OPTIONS="halt_on_error=1:print_stacktrace=1"
# One harness: fuzz for $seconds, then print its figures; returns non-zero on a finding.
run_one() {
  local name="$1" corpus_name="${1%_fuzz}"
  local work="build-fuzz/corpus/$corpus_name" findings="build-fuzz/findings/$corpus_name" log="build-fuzz/$1.log"
  mkdir -p "$work" "$findings"
  [ -d "fuzz/corpus/$corpus_name" ] && cp -n fuzz/corpus/"$corpus_name"/* "$work"/ 2>/dev/null || true
  local dict=()
  [ -f "fuzz/$corpus_name.dict" ] && dict=(-dict="fuzz/$corpus_name.dict")
  echo "fuzz: $name for $seconds s (log $log)"
  if nice build-fuzz/fuzz/"$name" "$work" "${dict[@]}" -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 \
       -malloc_limit_mb=2048 -max_len=65536 -print_final_stats=1 -artifact_prefix="$findings/" > "$log" 2>&1; then
    local runs cov
    runs=$(grep -o 'stat::number_of_executed_units: *[0-9]*' "$log" | grep -o '[0-9]*$' || echo "?")
    cov=$(grep -Eo 'cov: [0-9]+ ft: [0-9]+' "$log" | tail -1 || echo "")
    echo "fuzz: $name passed: $runs executions in $seconds s, $cov, corpus $(ls "$work" | wc -l) inputs"
  else
    echo "fuzz: $name FAILED (finding in $findings/):" >&2
    grep -E "ERROR|runtime error|SUMMARY|Test unit written" "$log" | head -20 >&2
    return 1
  fi
}

# FUZZ_PARALLEL=1 runs the harnesses at once (one core each), else one after another.
status=0
if [ "${FUZZ_PARALLEL:-0}" = 1 ]; then
  pids=()
  for name in "${harnesses[@]}"; do run_one "$name" & pids+=($!); done
  for pid in "${pids[@]}"; do wait "$pid" || status=1; done
else
  for name in "${harnesses[@]}"; do run_one "$name" || status=1; done
fi
exit $status
