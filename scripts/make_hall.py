#!/usr/bin/env python3
"""Writes data/hall.obj and data/hall.mtl: a warehouse hall with five rack rows, the
single large room of configs/hall.yaml (docs/cluster.md: an operator build split over
MPI ranks; at configs/hall.yaml's max_patch_edge_m of 0.19 m the hall meshes into about 1M patches).

    python3 scripts/make_hall.py [--out DIR]     # default: the repository's data/

Plan (x east, y north, z up, metres): the hall is 40 x 25 m, 8 m high; racks are
closed boxes 24 x 1.2 x 5 m, their rows along x at y = 3.5, 7.5, ..., 19.5 (aisles of
2.8 m between them). Surfaces: floor (faces up), ceiling (down), walls (into the hall),
racks (outwards). Deterministic and small (a few dozen triangles): running the script
again rewrites the same bytes.
"""
import argparse
import os

W, D, H = 40.0, 25.0, 8.0
RACK_X = (8.0, 32.0)
RACK_DEPTH, RACK_H = 1.2, 5.0
RACK_Y = [3.5 + 4.0 * i for i in range(5)]

vertices = []
groups = {}  # name -> list of triangles (vertex indices, 1-based)


def quad(group, a, b, c, d):
    """A planar quad a-b-c-d, counter-clockwise seen from the side its normal points to."""
    ids = []
    for p in (a, b, c, d):
        vertices.append(p)
        ids.append(len(vertices))
    groups.setdefault(group, []).extend([(ids[0], ids[1], ids[2]), (ids[0], ids[2], ids[3])])


def main():
    here = os.path.dirname(os.path.abspath(__file__))
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--out", default=os.path.join(here, "..", "data"), help="folder for hall.obj and hall.mtl")
    out = parser.parse_args().out
    # The hall, every face into it.
    quad("floor", (0, 0, 0), (W, 0, 0), (W, D, 0), (0, D, 0))
    quad("ceiling", (0, 0, H), (0, D, H), (W, D, H), (W, 0, H))
    quad("walls", (0, 0, 0), (0, 0, H), (W, 0, H), (W, 0, 0))        # south, normal +y
    quad("walls", (0, D, 0), (W, D, 0), (W, D, H), (0, D, H))        # north, normal -y
    quad("walls", (0, 0, 0), (0, D, 0), (0, D, H), (0, 0, H))        # west, normal +x
    quad("walls", (W, 0, 0), (W, 0, H), (W, D, H), (W, D, 0))        # east, normal -x
    # Rack rows: closed boxes, every face outwards (their bottoms rest on the floor).
    x0, x1 = RACK_X
    for y0 in RACK_Y:
        y1 = y0 + RACK_DEPTH
        quad("racks", (x0, y0, RACK_H), (x1, y0, RACK_H), (x1, y1, RACK_H), (x0, y1, RACK_H))  # top, +z
        quad("racks", (x0, y0, 0), (x1, y0, 0), (x1, y0, RACK_H), (x0, y0, RACK_H))            # south, -y
        quad("racks", (x0, y1, 0), (x0, y1, RACK_H), (x1, y1, RACK_H), (x1, y1, 0))            # north, +y
        quad("racks", (x0, y0, 0), (x0, y0, RACK_H), (x0, y1, RACK_H), (x0, y1, 0))            # west, -x
        quad("racks", (x1, y0, 0), (x1, y1, 0), (x1, y1, RACK_H), (x1, y0, RACK_H))            # east, +x
    os.makedirs(out, exist_ok=True)
    with open(os.path.join(out, "hall.mtl"), "w", newline="\n") as f:
        f.write("# written by scripts/make_hall.py\n")
        for name, kd in (("floor", 0.3), ("ceiling", 0.7), ("walls", 0.5), ("racks", 0.4)):
            f.write(f"newmtl {name}\nKd {kd} {kd} {kd}\n")
    with open(os.path.join(out, "hall.obj"), "w", newline="\n") as f:
        f.write("# A warehouse hall with five rack rows, written by scripts/make_hall.py (z up, metres)\n")
        f.write("mtllib hall.mtl\n")
        for v in vertices:
            f.write("v {:g} {:g} {:g}\n".format(*v))
        for name in sorted(groups):
            f.write(f"g {name}\nusemtl {name}\n")
            for tri in groups[name]:
                f.write("f " + " ".join(str(i) for i in tri) + "\n")


if __name__ == "__main__":
    main()
