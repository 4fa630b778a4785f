#!/usr/bin/env python3
"""Times whole `ilp run` jobs from a cold start (--no-cache): the median of N runs of
each job, its phases (timings.json), verification's share, and the estimate the run
printed before its work, as a Markdown table (docs/benchmarks.md).

    python3 scripts/bench_jobs.py [--ilp ./build/ilp] [--runs 3] [--threads N] [--calibrate] configs/classroom.yaml ...

Several binaries (--ilp A --ilp B) are measured side by side: each run of each job runs
every binary in turn, so that a load that comes and goes falls on all of them."""
import argparse, json, re, statistics, subprocess, tempfile, time, os


def run_once(ilp, job, out, extra=(), calibrate=False):
    env, speed = None, None
    if calibrate:  # the machine probed again just before the run, in a cache of the run's own
        env = dict(os.environ, XDG_CACHE_HOME=out + ".cache")
        c = subprocess.run([ilp, "calibrate"], env=env, capture_output=True, text=True, check=True)
        speed = re.search(r"rays ([0-9.]+)x, memory ([0-9.]+)x, dense ([0-9.]+)x", c.stdout)
    start = time.monotonic()
    p = subprocess.run([ilp, "run", job, "--no-cache", "--out", out, *extra], capture_output=True, text=True, env=env)
    wall = time.monotonic() - start
    if p.returncode not in (0, 2):
        raise SystemExit(f"{ilp} run {job}: exit {p.returncode}\n{p.stderr[-2000:]}")
    # Per room of a building job ("room K of N:" starts each), else the whole log: the
    # whole run's line of a job of several variants, else the sum of its variants' totals
    # (one variant; luminaire groups print one per group's variant).
    estimate = None
    for part in re.split(r"\nroom [0-9]+ of [0-9]+:", p.stderr):
        m = re.search(r"estimate: the whole run[^\n]*about ([0-9.]+) s", part)
        found = [m.group(1)] if m else [str(sum(float(x) for x in re.findall(r"estimate: in all about ([0-9.]+) s", part)))]
        found = [x for x in found if float(x) > 0.0]
        if found:
            estimate = (estimate or 0.0) + float(found[0])
    with open(os.path.join(out, "timings.json")) as f:
        t = json.load(f)["timings_s"]
    return {"wall": wall, "estimate": estimate, "verification": t.get("verification", 0.0),
            "operator": t.get("operator", 0.0), "exit": p.returncode,
            "speed": "/".join(speed.groups()) if speed else None}


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--ilp", action="append")
    ap.add_argument("--runs", type=int, default=3)
    ap.add_argument("--threads", type=int, help="passed to ilp run (default: the job's solver.threads)")
    ap.add_argument("--calibrate", action="store_true",
                    help="probe the machine (ilp calibrate) just before each run, so that its estimate is of the machine's speed then")
    ap.add_argument("jobs", nargs="+")
    a = ap.parse_args()
    binaries = a.ilp or ["./build/ilp"]
    extra = ["--threads", str(a.threads)] if a.threads is not None else []
    results = {(b, j): [] for b in binaries for j in a.jobs}
    with tempfile.TemporaryDirectory() as tmp:
        for r in range(a.runs):
            for j in a.jobs:
                for i, b in enumerate(binaries):
                    results[(b, j)].append(run_once(b, j, os.path.join(tmp, f"{i}_{r}_{os.path.basename(j)}"), extra,
                                                       a.calibrate))
    print("| job | binary | wall s (median of %d) | runs | operator s | verification s | verification share | "
          "estimate s (median) | estimate / measured (median of the runs') | machine: rays/memory/dense (ilp calibrate) |" % a.runs)
    print("|---|---|---|---|---|---|---|---|---|---|")
    for j in a.jobs:
        for b in binaries:
            rs = results[(b, j)]
            wall = statistics.median(x["wall"] for x in rs)
            op = statistics.median(x["operator"] for x in rs)
            ver = statistics.median(x["verification"] for x in rs)
            ests = [x["estimate"] for x in rs if x["estimate"]]
            est = f"{statistics.median(ests):.1f}" if ests else "-"
            ratio = f"{statistics.median(x['estimate'] / x['wall'] for x in rs if x['estimate']):.2f}" if ests else "-"
            speeds = ", ".join(x["speed"] for x in rs if x["speed"]) or "-"
            each = ", ".join("%.1f" % x["wall"] for x in rs)
            print(f"| {j} | {b} | {wall:.1f} | {each} | {op:.1f} | {ver:.1f} | "
                  f"{100 * ver / wall:.0f} % | {est} | {ratio} | {speeds} |")


if __name__ == "__main__":
    main()
