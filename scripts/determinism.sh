#!/usr/bin/env bash
# Issue 21: the same job and seed give a byte-identical result.json on an idle and on a
# busy machine. Runs a job (default configs/office.yaml, as shipped) once as it is and
# once under `nice` beside two CPU burners, without the operator cache, and compares
# the two result.json files (timings are in timings.json, not compared).
#   scripts/determinism.sh [JOB.yaml] [ILP_BINARY]
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
job="${1:-$root/configs/office.yaml}"
ilp="${2:-$root/build/ilp}"
work="$(mktemp -d)"
burners=()
cleanup() {
  for pid in "${burners[@]}"; do kill "$pid" 2>/dev/null || true; done
  rm -rf "$work"
}
trap cleanup EXIT

start=$(date +%s%N)
"$ilp" run "$job" --out "$work/idle" --no-cache -q > "$work/idle.log" 2>&1
idle_ms=$(( ($(date +%s%N) - start) / 1000000 ))

for _ in 1 2; do
  ( while :; do :; done ) &
  burners+=("$!")
done
start=$(date +%s%N)
nice -n 10 "$ilp" run "$job" --out "$work/busy" --no-cache -q > "$work/busy.log" 2>&1
busy_ms=$(( ($(date +%s%N) - start) / 1000000 ))
for pid in "${burners[@]}"; do kill "$pid"; done
burners=()

echo "idle run $((idle_ms / 1000)).$(( (idle_ms % 1000) / 100 )) s, busy run (nice 10, two CPU burners) $((busy_ms / 1000)).$(( (busy_ms % 1000) / 100 )) s"
if cmp -s "$work/idle/result.json" "$work/busy/result.json"; then
  echo "result.json byte-identical ($(wc -c < "$work/idle/result.json") bytes, sha256 $(sha256sum < "$work/idle/result.json" | cut -c1-16))"
else
  echo "result.json DIFFERS:"
  diff "$work/idle/result.json" "$work/busy/result.json" | head -40
  exit 1
fi
