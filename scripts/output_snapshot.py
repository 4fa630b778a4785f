#!/usr/bin/env python3
"""Snapshots what every shipped job prints and writes, timing fields masked, so that a
change of structure can be shown to change no result.

    python3 scripts/output_snapshot.py take ./build/ilp /tmp/before   # before the change
    python3 scripts/output_snapshot.py take ./build/ilp /tmp/after    # after it
    python3 scripts/output_snapshot.py compare /tmp/before /tmp/after # exit 1 and a diff if any differ

For each job in configs/ with a mounting surface, `ilp run --no-cache` (2 threads, a
sweep too where the job has one); for every job, `ilp solve` (placed luminaires); its
stdout, result.json, grid.csv and sweep.csv. Masked: every duration in seconds
(result.json's timings_s and each attempt's seconds; numbers followed by " s" in the
printed text; CSV columns named *_s), peak memory, and the output folder's path.
"""
import difflib
import json
import os
import re
import subprocess
import sys
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
CONFIGS = sorted((ROOT / "configs").glob("*.yaml"))
SECONDS = re.compile(r"\d+(\.\d+)?(e[-+]?\d+)? ?s\b")
MEMORY = re.compile(r"(peak (resident )?memory[^\d]*)[\d.]+ ?[KMGT]?i?B", re.IGNORECASE)
DURATION_KEYS = {"timings_s", "seconds", "build_seconds", "verify_seconds", "search_seconds"}


def mask_text(text, out_dir):
    text = text.replace(str(out_dir), "<out>")
    text = MEMORY.sub(r"\1<mem>", text)
    return SECONDS.sub("<t> s", text)


def mask_json(value):
    if isinstance(value, dict):
        return {k: ("<t>" if k in DURATION_KEYS or k.endswith("_seconds") else mask_json(v)) for k, v in value.items()}
    if isinstance(value, list):
        return [mask_json(v) for v in value]
    return value


def run(cmd):
    p = subprocess.run(cmd, cwd=ROOT, capture_output=True, text=True)
    return p.returncode, p.stdout


def take(ilp, dest):
    dest.mkdir(parents=True, exist_ok=True)
    for config in CONFIGS:
        name = config.stem
        text = config.read_text()
        jobs = [("solve", [ilp, "solve", str(config), "--threads", "2", "--quiet"])]
        if "mounting_surface" in text:
            jobs.append(("run", [ilp, "run", str(config), "--threads", "2", "--quiet", "--no-cache"]))
            if re.search(r"^sweep:", text, re.MULTILINE):
                jobs.append(("sweep", [ilp, "sweep", str(config), "--threads", "2", "--quiet", "--no-cache"]))
        for command, cmd in jobs:
            with tempfile.TemporaryDirectory() as tmp:
                out_dir = Path(tmp) / "out"
                if command != "solve":
                    cmd = cmd + ["--out", str(out_dir)]
                code, stdout = run(cmd)
                print(f"{name} {command}: exit {code}", file=sys.stderr)
                (dest / f"{name}.{command}.stdout").write_text(f"exit {code}\n" + mask_text(stdout, out_dir))
                for produced in ("result.json", "grid.csv", "sweep.csv"):
                    path = out_dir / produced
                    if not path.exists():
                        continue
                    if produced.endswith(".json"):
                        body = json.dumps(mask_json(json.loads(path.read_text())), indent=1, sort_keys=True)
                    else:
                        body = path.read_text()
                    (dest / f"{name}.{command}.{produced}").write_text(mask_text(body, out_dir))


def mask_csv_seconds(text):
    """Blanks the columns whose header ends in _s (durations, e.g. sweep.csv's search_s)."""
    lines = text.splitlines(keepends=True)
    if not lines:
        return text
    timed = [i for i, h in enumerate(lines[0].rstrip("\n").split(",")) if h.endswith("_s")]
    out = [lines[0]]
    for line in lines[1:]:
        fields = line.rstrip("\n").split(",")
        for i in timed:
            if i < len(fields):
                fields[i] = "<t>"
        out.append(",".join(fields) + "\n")
    return "".join(out)


def compare(a, b):
    names = sorted({p.name for p in a.iterdir()} | {p.name for p in b.iterdir()})
    differing = 0
    for name in names:
        pa, pb = a / name, b / name
        read = (lambda p: mask_csv_seconds(p.read_text())) if name.endswith(".csv") else (lambda p: p.read_text())
        la = read(pa).splitlines(keepends=True) if pa.exists() else []
        lb = read(pb).splitlines(keepends=True) if pb.exists() else []
        if la != lb:
            differing += 1
            sys.stdout.writelines(difflib.unified_diff(la, lb, str(pa), str(pb), n=1))
    print(f"{len(names) - differing} identical, {differing} differing", file=sys.stderr)
    return 1 if differing else 0


def main():
    if len(sys.argv) == 4 and sys.argv[1] == "take":
        take(os.path.abspath(sys.argv[2]), Path(sys.argv[3]))
        return 0
    if len(sys.argv) == 4 and sys.argv[1] == "compare":
        return compare(Path(sys.argv[2]), Path(sys.argv[3]))
    print(__doc__, file=sys.stderr)
    return 2


if __name__ == "__main__":
    sys.exit(main())
