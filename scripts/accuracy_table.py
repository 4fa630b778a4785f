#!/usr/bin/env python3
"""Markdown table of an `ilp accuracy` CSV: medians over seeds per series and k.

    python3 scripts/accuracy_table.py docs/accuracy/office/accuracy.csv
"""
import csv
import statistics
import sys
from collections import defaultdict


def main(path):
    groups = defaultdict(list)
    with open(path, newline="") as f:
        for row in csv.DictReader(f):
            key = (row["strategy"], row["indirect"], int(row["rays_per_row"]), int(row["k"]))
            groups[key].append(row)
    print("| strategy | indirect | rays/row | k | k % | build s | eval µs | RMS total % | max total % "
          "| RMS indirect % | predicted % | predicted / RMS |")
    print("|---|---|---|---|---|---|---|---|---|---|---|---|")
    for key in sorted(groups, key=lambda k: (k[0], k[1], k[2], k[3])):
        rows = groups[key]
        med = lambda name: statistics.median(float(r[name]) for r in rows)
        rms, predicted = med("rms_rel_error_total"), med("predicted_rms_rel_error_total")
        ratio = f"{predicted / rms:.2f}" if predicted > 0 and rms > 0 else "–"
        print(f"| {key[0]} | {key[1]} | {key[2]} | {key[3]} | {100 * med('sample_fraction'):.0f} "
              f"| {med('build_seconds'):.3f} | {med('evaluation_microseconds'):.2f} | {100 * rms:.2f} "
              f"| {100 * med('max_rel_error_total'):.1f} | {100 * med('rms_rel_error_indirect'):.2f} "
              f"| {100 * predicted:.2f} | {ratio} |")


if __name__ == "__main__":
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    main(sys.argv[1])
