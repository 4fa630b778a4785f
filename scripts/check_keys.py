#!/usr/bin/env python3
"""Checks that core/ and optimizer/ spell no key of the job file (docs/architecture.md).

    python3 scripts/check_keys.py        # exit 1 and every string literal that does

Below job/, a message names a setting with setting_name (core/base/setting.h) and the job
layer says how its file spells it (job/setting_keys.cpp). A key here is a path into one of
the file's sections ("luminaires.zone", "grids[].spacing_m", "goals." + name). An option
struct's own field names (SceneOptions::max_patch_edge_m) are core's names and pass.
"""
import re
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
SECTIONS = ("scene", "luminaires", "goals", "grids", "solver", "verification", "optimizer", "output",
            "constraints", "energy", "sweep", "rooms", "scenarios", "report")
PATH = re.compile(r"\b(" + "|".join(SECTIONS) + r")(\.|\[)")
LITERAL = re.compile(r'"((?:[^"\\\n]|\\.)*)"')
INCLUDE = re.compile(r"^\s*#\s*include")


def main():
    bad = []
    for folder in ("core", "optimizer"):
        for path in sorted((ROOT / folder).rglob("*")):
            if path.suffix not in (".h", ".cpp"):
                continue
            for n, line in enumerate(path.read_text().split("\n"), 1):
                if INCLUDE.match(line):
                    continue
                for m in LITERAL.finditer(line):
                    if PATH.search(m.group(1)):
                        bad.append(f"{path.relative_to(ROOT)}:{n}: \"{m.group(1)}\"")
    for line in bad:
        print(line)
    print(f"keys: {len(bad)} string literals spell a key of the job file" if bad
          else "keys: no string of core/ or optimizer/ spells a key of the job file")
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())
