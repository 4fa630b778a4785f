#!/usr/bin/env python3
"""How cost grows: runs `ilp bench` on one job for several patch sizes and sample
fractions (one process each, so peak memory is per run), appends rows to a CSV and
fits power laws cost ~ c * x^p by least squares in log-log.

    python3 scripts/bench_scaling.py configs/classroom.yaml --edges 1.0,0.5,0.35 \
        --fractions 0.01,0.02,0.04 --out docs/benchmarks/classroom_scaling.csv

Patch sizes run at the job's sample fraction scaled to keep k = fraction x patches;
fractions run at the first edge that is not the largest (the middle scene)."""
import argparse
import csv
import math
import os
import subprocess
import sys


def run(binary, config, out, edge=None, fraction=None, skip_full=True):
    cmd = [binary, "bench", config, "--csv", out, "-q"]
    if edge:
        cmd += ["--patch-edge", str(edge)]
    if fraction:
        cmd += ["--sample-fraction", str(fraction)]
    if skip_full:
        cmd.append("--skip-full-solve")
    print("$", " ".join(cmd), file=sys.stderr, flush=True)
    subprocess.run(cmd, check=True, stdout=subprocess.DEVNULL)


def fit(xs, ys):
    """Exponent p and factor c of y = c x^p (least squares in log-log)."""
    lx = [math.log(x) for x in xs]
    ly = [math.log(y) for y in ys]
    n = len(lx)
    mx, my = sum(lx) / n, sum(ly) / n
    sxx = sum((a - mx) ** 2 for a in lx)
    p = sum((a - mx) * (b - my) for a, b in zip(lx, ly)) / sxx
    return p, math.exp(my - p * mx)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("config")
    ap.add_argument("--edges", default="1.0,0.5,0.35")
    ap.add_argument("--fractions", default="0.01,0.02,0.04")
    ap.add_argument("--out", required=True)
    ap.add_argument("--binary", default=os.path.join(os.path.dirname(__file__), "..", "build", "ilp"))
    a = ap.parse_args()
    edges = [float(e) for e in a.edges.split(",")]
    fractions = [float(f) for f in a.fractions.split(",")]
    if os.path.exists(a.out):
        os.remove(a.out)
    for e in edges:
        run(a.binary, a.config, a.out, edge=e, fraction=fractions[len(fractions) // 2])
    for f in fractions:
        if f != fractions[len(fractions) // 2]:
            run(a.binary, a.config, a.out, edge=edges[len(edges) // 2], fraction=f)
    rows = list(csv.DictReader(open(a.out)))
    by_edge = rows[: len(edges)]
    mid_edge = by_edge[len(edges) // 2]
    by_k = sorted([mid_edge] + rows[len(edges):], key=lambda r: int(r["k"]))
    print("| patches | k | build s | goal rows s | direct s | k x k solve s | peak GB | evaluations/s |")
    print("|---|---|---|---|---|---|---|---|")
    for r in by_edge + rows[len(edges):]:
        print(f"| {int(r['patches']):,} | {int(r['k']):,} | {float(r['build_s']):.2f} | {float(r['goal_rows_s']):.2f} | "
              f"{float(r['direct_s']):.2f} | {float(r['solve_s']):.2f} | {float(r['build_peak_gb']):.2f} | "
              f"{float(r['evaluations_per_s']):.0f} |")
    print()
    n = [float(r["patches"]) for r in by_edge]
    for key, label in (("build_s", "build time"), ("build_peak_gb", "peak memory"),
                       ("evaluations_per_s", "evaluations per second")):
        p, _ = fit(n, [float(r[key]) for r in by_edge])
        print(f"- {label} ~ patches^{p:.2f} (k = {fractions[len(fractions) // 2]} x patches)")
    goals = [float(r["goal_patches"]) for r in by_edge]
    p, _ = fit(goals, [float(r["evaluations_per_s"]) for r in by_edge])
    print(f"- evaluations per second ~ goal patches^{p:.2f} (the goal patches grow with the mesh)")
    k = [float(r["k"]) for r in by_k]
    for key, label in (("build_s", "build time"), ("solve_s", "k x k solve"), ("build_peak_gb", "peak memory")):
        p, _ = fit(k, [float(r[key]) for r in by_k])
        print(f"- {label} ~ k^{p:.2f} ({int(float(mid_edge['patches'])):,} patches)")


if __name__ == "__main__":
    main()
