#!/usr/bin/env bash
# Builds the libFuzzer harness of the photometric readers (fuzz/photometry_fuzz.cpp) with
# clang and ASan/UBSan against the photometry sources only (core/light/photometry.cpp and
# its two readers), then fuzzes for SECONDS (default 300) on one core. The working corpus
# grows in build-fuzz/photometry_corpus (seeded from fuzz/corpus/photometry, which is left
# untouched); crashes land in build-fuzz/.
#   scripts/fuzz_photometry.sh [SECONDS] [extra libFuzzer flags...]
# Needs clang (Debian package clang; scripts/setup.sh installs it).
set -euo pipefail
cd "$(dirname "$0")/.."
seconds="${1:-300}"
shift || true
out=build-fuzz
mkdir -p "$out/photometry_corpus"
clang++ -std=c++20 -g -O1 -fsanitize=fuzzer,address,undefined -fno-sanitize-recover=undefined \
  -I. -I/usr/include/eigen3 fuzz/photometry_fuzz.cpp core/light/photometry.cpp \
  core/light/ies_reader.cpp core/light/eulumdat_reader.cpp core/base/error.cpp -o "$out/photometry_fuzz"
cp -n fuzz/corpus/photometry/*.ies fuzz/corpus/photometry/*.ldt "$out/photometry_corpus/" 2>/dev/null || true
cd "$out"
exec nice ./photometry_fuzz -max_total_time="$seconds" -max_len=8192 -timeout=10 -rss_limit_mb=2048 \
  -dict=../fuzz/photometry.dict -print_final_stats=1 "$@" photometry_corpus
