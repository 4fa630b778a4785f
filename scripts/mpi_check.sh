#!/usr/bin/env bash
# The MPI checks (docs/cluster.md), run by .ci/run after the test suite:
#  1. configs/floor.yaml (seven rooms) under `mpirun -np 2` gives the same files, byte
#     for byte, as the single-process run (timings.json, the one file of wall-clock
#     times, left out; result.json also compared with any "timings"/"seconds" key
#     masked, in case a future version adds one);
#  2. a building whose second room (run by rank 1) names a mounting surface the model
#     lacks: exit 1, one "error:" line, no output folder;
#  3. a sweep under mpirun (run by rank 0 alone) gives the single-process sweep.csv;
#  4. a rank killed mid-run: the job ends (non-zero exit) and writes no output folder;
#  5. a single-room job (configs/office.yaml, its hit patches in blocks of 400) whose
#     operator build is split over the ranks: result.json is the same, timings masked,
#     for 1 process, mpirun -np 2, -np 3 and -np 4 (one thread per rank) and -np 2 with
#     2 threads per rank, and each rank's peak memory is printed;
#  6. a rank out of memory in the split preparation (rank 1's address space capped: its
#     BVH cannot be built): exit 1, one "error:" line, nothing written;
#  7. a single-room job that cannot be planned (configs/office_fixed.yaml places no
#     luminaire: a job for ilp solve) under mpirun: exit 1, one "error:" line.
# Needs build/ilp and Open MPI (scripts/setup.sh installs libopenmpi-dev openmpi-bin).
set -euo pipefail
cd "$(dirname "$0")/.."
repo=$PWD
ilp=$repo/build/ilp
[ -x "$ilp" ] || { echo "mpi_check: build/ilp missing (bash scripts/setup.sh)" >&2; exit 1; }
command -v mpirun > /dev/null || { echo "mpi_check: mpirun missing (apt-get install openmpi-bin)" >&2; exit 1; }
mpi=(mpirun --oversubscribe -np 2)
[ "$(id -u)" -eq 0 ] && mpi+=(--allow-run-as-root)
tmp=$(mktemp -d /tmp/ilp_mpi_check.XXXXXX)
trap 'rm -rf "$tmp"' EXIT
fail() { echo "mpi_check: FAIL: $*" >&2; exit 1; }

# The single-process run fills a fresh cache; the 2-rank run builds its operators anew.
echo "mpi_check: configs/floor.yaml, 1 process"
"$ilp" run configs/floor.yaml --out "$tmp/one" --cache "$tmp/cache" --threads 1 -q > "$tmp/one.log" 2>&1 \
  || { cat "$tmp/one.log"; fail "the single-process run failed"; }
echo "mpi_check: configs/floor.yaml, mpirun -np 2"
"${mpi[@]}" "$ilp" run configs/floor.yaml --out "$tmp/two" --no-cache --threads 1 -q > "$tmp/two.log" 2>&1 \
  || { cat "$tmp/two.log"; fail "the 2-rank run failed"; }
diff -r -x timings.json "$tmp/one" "$tmp/two" > "$tmp/diff.txt" || { head -40 "$tmp/diff.txt"; fail "files differ between 1 and 2 ranks"; }
python3 - "$tmp/one/result.json" "$tmp/two/result.json" <<'PY' || fail "result.json differs (timings masked)"
import json, sys
def mask(v):
    if isinstance(v, dict):
        return {k: ("*" if "timings" in k or "seconds" in k else mask(x)) for k, x in v.items()}
    if isinstance(v, list):
        return [mask(x) for x in v]
    return v
a, b = (mask(json.load(open(p))) for p in sys.argv[1:3])
sys.exit(0 if a == b else 1)
PY
[ -f "$tmp/two/timings.json" ] || fail "the 2-rank run wrote no timings.json"
files=$(cd "$tmp/one" && find . -type f | wc -l)
echo "mpi_check: ok, $files files identical (timings.json aside)"

# A sweep under mpirun (not spread over ranks yet: rank 0 runs it, the other waits) gives
# the single-process sweep.csv, its time columns (*_s) masked.
sweep=(sweep configs/office.yaml --set goals.work_plane.average_lux=300,500 --cache "$tmp/cache" --threads 1 -q)
"$ilp" "${sweep[@]}" --out "$tmp/sweep_one" > "$tmp/sweep_one.log" 2>&1 || { cat "$tmp/sweep_one.log"; fail "the sweep failed"; }
"${mpi[@]}" "$ilp" "${sweep[@]}" --out "$tmp/sweep_two" > "$tmp/sweep_two.log" 2>&1 \
  || { cat "$tmp/sweep_two.log"; fail "the sweep under mpirun failed"; }
python3 - "$tmp/sweep_one/sweep.csv" "$tmp/sweep_two/sweep.csv" <<'PY' || fail "sweep.csv differs (times masked)"
import csv, sys
def rows(path):
    table = list(csv.reader(open(path)))
    keep = [i for i, name in enumerate(table[0]) if not name.endswith("_s")]
    return [[row[i] for i in keep] for row in table]
sys.exit(0 if rows(sys.argv[1]) == rows(sys.argv[2]) else 1)
PY
echo "mpi_check: ok, the sweep under mpirun gives the same sweep.csv (times masked)"

# A room that only rank 1 sees fail: its mounting surface is not in the model.
mkdir -p "$tmp/bad/configs"
ln -s "$repo/data" "$tmp/bad/data"
sed 's/mounting_surface: office_2_ceiling/mounting_surface: office_2_roof/' configs/floor.yaml > "$tmp/bad/configs/floor.yaml"
grep -q office_2_roof "$tmp/bad/configs/floor.yaml" || fail "could not make the failing job"
set +e
"${mpi[@]}" "$ilp" run "$tmp/bad/configs/floor.yaml" --out "$tmp/bad_out" --cache "$tmp/cache" --threads 1 -q \
  > "$tmp/bad.log" 2> "$tmp/bad.err"
code=$?
set -e
[ "$code" -eq 1 ] || { cat "$tmp/bad.err"; fail "a failing rank gave exit $code, not 1"; }
[ "$(grep -c '^error:' "$tmp/bad.err")" -eq 1 ] || { cat "$tmp/bad.err"; fail "not exactly one error line"; }
grep -q office_2_roof "$tmp/bad.err" || { cat "$tmp/bad.err"; fail "the error does not name the bad surface"; }
[ ! -e "$tmp/bad_out" ] || fail "a failing rank left an output folder"
echo "mpi_check: ok, a failing rank: exit 1, $(grep '^error:' "$tmp/bad.err" | cut -c1-100)..."

# A rank killed mid-run (rank 1, a few seconds in): the job ends, nothing written.
set +e
"${mpi[@]}" "$ilp" run configs/floor.yaml --out "$tmp/killed" --no-cache --threads 1 -q > "$tmp/kill.log" 2>&1 &
launcher=$!
victim=""
for _ in $(seq 1 100); do
  sleep 0.1
  for pid in $(pgrep -P "$launcher" 2> /dev/null); do
    if tr '\0' '\n' < "/proc/$pid/environ" 2> /dev/null | grep -qx OMPI_COMM_WORLD_RANK=1; then victim=$pid; fi
  done
  [ -n "$victim" ] && break
done
[ -n "$victim" ] || { kill "$launcher"; wait "$launcher"; fail "found no rank 1 to kill"; }
sleep 2
kill -9 "$victim"
wait "$launcher"
code=$?
set -e
[ "$code" -ne 0 ] || fail "the job with a killed rank exited 0"
[ ! -e "$tmp/killed" ] || fail "a killed rank left an output folder"
echo "mpi_check: ok, a killed rank: exit $code, no output folder"

# A single room's operator build split over 2, 3 and 4 ranks: the same result.json.
mkdir -p "$tmp/split/configs"
ln -s "$repo/data" "$tmp/split/data"
sed 's/^solver:$/solver:\n  hit_block_patches: 400/' configs/office.yaml > "$tmp/split/configs/office.yaml"
grep -q "hit_block_patches: 400" "$tmp/split/configs/office.yaml" || fail "could not make the split job"
split_job=("$tmp/split/configs/office.yaml" --no-cache -q)
echo "mpi_check: office (split build), 1 process"
"$ilp" run "${split_job[@]}" --threads 1 --out "$tmp/split_1" > "$tmp/split_1.log" 2>&1 \
  || [ $? -eq 2 ] || { cat "$tmp/split_1.log"; fail "the single-process office failed"; }
# ranks:threads per rank (the sources split over 2, 3 and 4 ranks; 2 threads per rank too).
for run in 2:1 3:1 4:1 2:2; do
  n=${run%:*} threads=${run#*:}
  echo "mpi_check: office (split build), mpirun -np $n, $threads thread(s) per rank"
  code=0
  mpirun --oversubscribe $([ "$(id -u)" -eq 0 ] && echo --allow-run-as-root) -np $n "$ilp" run "${split_job[@]}" \
    --threads "$threads" --out "$tmp/split_$n" > "$tmp/split_$n.log" 2>&1 || code=$?
  [ "$code" -eq 0 ] || [ "$code" -eq 2 ] || { cat "$tmp/split_$n.log"; fail "the $n-rank office failed (exit $code)"; }
  grep -q "operator build split over $n ranks" "$tmp/split_$n.log" || { cat "$tmp/split_$n.log"; fail "the $n-rank build was not split"; }
  grep -q "^peak memory per rank after the operator build: 0: .*, $((n - 1)): " "$tmp/split_$n.log" \
    || { cat "$tmp/split_$n.log"; fail "no peak memory line for $n ranks"; }
  python3 - "$tmp/split_1/result.json" "$tmp/split_$n/result.json" <<'PY' || fail "result.json differs between 1 and $n ranks x $threads threads"
import json, sys
def mask(v):
    if isinstance(v, dict):
        return {k: ("*" if "timings" in k or "seconds" in k else mask(x)) for k, x in v.items()}
    if isinstance(v, list):
        return [mask(x) for x in v]
    return v
a, b = (mask(json.load(open(p))) for p in sys.argv[1:3])
sys.exit(0 if a == b else 1)
PY
  if [ "$n" -eq 3 ]; then peak3=$(grep '^peak memory per rank after' "$tmp/split_3.log"); fi
  rm -rf "$tmp/split_$n"
done
echo "mpi_check: ok, a split build gives the same result.json on 1, 2, 3 and 4 ranks (and 2 ranks x 2 threads); $peak3"

# Rank 1 runs out of memory in the split preparation (its address space capped at 400 MB:
# Embree cannot create its device) while rank 0 goes on to the build's first exchange:
# one message, exit 1, no output folder.
set +e
mpirun --oversubscribe $([ "$(id -u)" -eq 0 ] && echo --allow-run-as-root) -np 2 bash -c \
  '[ "$OMPI_COMM_WORLD_RANK" = 1 ] && ulimit -v 400000; exec "$@"' rank "$ilp" run "${split_job[@]}" --threads 1 \
  --out "$tmp/split_oom" > "$tmp/split_oom.log" 2> "$tmp/split_oom.err"
code=$?
set -e
[ "$code" -eq 1 ] || { cat "$tmp/split_oom.err"; fail "a rank out of memory gave exit $code, not 1"; }
[ "$(grep -c '^error:' "$tmp/split_oom.err")" -eq 1 ] || { cat "$tmp/split_oom.err"; fail "not exactly one error line"; }
[ ! -e "$tmp/split_oom" ] || fail "a rank out of memory left an output folder"
echo "mpi_check: ok, a rank out of memory in the split preparation: exit 1, $(grep '^error:' "$tmp/split_oom.err" | cut -c1-100)"

# A job every rank fails to plan the same way: one message (rank 0's), exit 1 on every rank.
set +e
"${mpi[@]}" "$ilp" run configs/office_fixed.yaml --out "$tmp/unplanned" --no-cache -q > "$tmp/unplanned.log" \
  2> "$tmp/unplanned.err"
code=$?
set -e
[ "$code" -eq 1 ] || { cat "$tmp/unplanned.err"; fail "a job that cannot be planned gave exit $code, not 1"; }
[ "$(grep -c '^error:' "$tmp/unplanned.err")" -eq 1 ] || { cat "$tmp/unplanned.err"; fail "not exactly one error line"; }
grep -q 'ilp solve' "$tmp/unplanned.err" || { cat "$tmp/unplanned.err"; fail "the error does not say to use ilp solve"; }
[ ! -e "$tmp/unplanned" ] || fail "a job that cannot be planned left an output folder"
echo "mpi_check: ok, a job that cannot be planned under mpirun: exit 1, $(grep '^error:' "$tmp/unplanned.err" | cut -c1-100)"
