#!/usr/bin/env python3
"""Checks that the modules include only the layers below them (docs/architecture.md).

    python3 scripts/check_layers.py        # exit 1 and every include that runs back up

core/'s folders are layers, each allowed the ones listed for it; the modules above core
likewise. An include of a folder not in the list is an arrow back up (or across).
"""
import re
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
# Each folder and the folders its sources may include (besides its own).
CORE = {
    "core/base": [],
    "core/energy": ["core/base"],
    "core/light": ["core/base"],
    "core/scene": ["core/base", "core/light"],
    "core/transport": ["core/base", "core/light", "core/scene"],
    "core/grid": ["core/base", "core/light", "core/scene", "core/transport"],
    "core/exact": ["core/base", "core/light", "core/scene", "core/transport"],
    "core/operator": ["core/base", "core/light", "core/scene", "core/transport"],
    "core/glare": ["core/base", "core/light"],
    "core/daylight": ["core/base"],
    "core/study": ["core/base", "core/light", "core/scene", "core/transport", "core/grid", "core/exact",
                   "core/operator"],
    "core/cost": ["core/base", "core/light", "core/scene", "core/transport", "core/grid", "core/exact",
                  "core/operator"],
}
ALL_CORE = list(CORE)
MODULES = {
    "optimizer": ALL_CORE,
    "output": ALL_CORE,
    "dist": [],
    "job": ALL_CORE + ["optimizer", "output"],
    "run": ALL_CORE + ["optimizer", "output", "job", "dist"],
    "apps": ALL_CORE + ["optimizer", "output", "job", "run", "dist", "apps"],
}
INCLUDE = re.compile(r'^\s*#\s*include\s+"([a-z_]+(?:/[a-z_]+)?)/[A-Za-z0-9_./]+"', re.MULTILINE)


def folder_of(include):
    parts = include.split("/")
    return "/".join(parts[:2]) if parts[0] == "core" else parts[0]


def main():
    bad = []
    rules = dict(CORE, **MODULES)
    for folder, allowed in rules.items():
        base = ROOT / folder
        if not base.is_dir():
            continue
        for path in sorted(base.rglob("*")):
            if path.suffix not in (".h", ".cpp") or (folder == "core" and path.parent.name == "core"):
                continue
            own = folder if not folder.startswith("core/") else folder
            for m in INCLUDE.finditer(path.read_text()):
                target = folder_of(m.group(0).split('"')[1])
                if target == own or target in allowed:
                    continue
                bad.append(f"{path.relative_to(ROOT)}: includes {m.group(0).split(chr(34))[1]} ({target} is not below {own})")
    for line in bad:
        print(line)
    print(f"layers: {len(bad)} includes run back up" if bad else "layers: every include runs down")
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())
