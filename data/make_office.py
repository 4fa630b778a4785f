#!/usr/bin/env python3
"""Writes data/office.obj and data/office.mtl: the small office the project ships.

A 6 x 4 x 3 m room (z up, metres) with floor, walls and ceiling as separate
surfaces, two desks (top surfaces desk_1 and desk_2, their frames separately) and a
partition panel between them. Room faces point into the room; furniture faces point
out of the solids, so every surface is lit on its front side. Run it again to
regenerate; the output is committed because it is small.
"""
import os

ROOM = (6.0, 4.0, 3.0)
DESK_SIZE = (1.6, 0.8)       # x, y
DESK_TOP_Z = 0.75
DESK_TOP_THICKNESS = 0.04
LEG = 0.05
DESKS = {"desk_1": (1.7, 1.6), "desk_2": (4.3, 1.6)}  # centres (x, y)
PARTITION = ((2.975, 0.5, 0.0), (3.025, 2.7, 1.5))   # min, max corners

vertices = []
groups = []  # (group, material, [quads as vertex index lists])


def vertex(p):
    vertices.append(p)
    return len(vertices)


def quad(group, material, a, b, c, d):
    """Adds quad a-b-c-d, counter-clockwise seen from its front."""
    ids = [vertex(p) for p in (a, b, c, d)]
    for g in groups:
        if g[0] == group:
            g[2].append(ids)
            return
    groups.append((group, material, [ids]))


def box(group, material, lo, hi, skip=(), top_group=None):
    """Six outward faces of an axis-aligned box; `skip` names faces to leave out."""
    x0, y0, z0 = lo
    x1, y1, z1 = hi
    faces = {
        "bottom": [(x0, y0, z0), (x0, y1, z0), (x1, y1, z0), (x1, y0, z0)],
        "top": [(x0, y0, z1), (x1, y0, z1), (x1, y1, z1), (x0, y1, z1)],
        "south": [(x0, y0, z0), (x1, y0, z0), (x1, y0, z1), (x0, y0, z1)],
        "north": [(x1, y1, z0), (x0, y1, z0), (x0, y1, z1), (x1, y1, z1)],
        "west": [(x0, y1, z0), (x0, y0, z0), (x0, y0, z1), (x0, y1, z1)],
        "east": [(x1, y0, z0), (x1, y1, z0), (x1, y1, z1), (x1, y0, z1)],
    }
    for name, corners in faces.items():
        if name in skip:
            continue
        quad(top_group if (name == "top" and top_group) else group, material, *corners)


def main():
    X, Y, Z = ROOM
    # Room: faces point inwards.
    quad("floor", "floor", (0, 0, 0), (X, 0, 0), (X, Y, 0), (0, Y, 0))
    quad("ceiling", "ceiling", (0, 0, Z), (0, Y, Z), (X, Y, Z), (X, 0, Z))
    quad("walls", "wall", (0, 0, 0), (0, Y, 0), (0, Y, Z), (0, 0, Z))      # x = 0
    quad("walls", "wall", (X, 0, 0), (X, 0, Z), (X, Y, Z), (X, Y, 0))      # x = X
    quad("walls", "wall", (0, 0, 0), (0, 0, Z), (X, 0, Z), (X, 0, 0))      # y = 0
    quad("walls", "wall", (0, Y, 0), (X, Y, 0), (X, Y, Z), (0, Y, Z))      # y = Y
    for name, (cx, cy) in DESKS.items():
        hx, hy = DESK_SIZE[0] / 2, DESK_SIZE[1] / 2
        box(name + "_frame", "desk", (cx - hx, cy - hy, DESK_TOP_Z - DESK_TOP_THICKNESS),
            (cx + hx, cy + hy, DESK_TOP_Z), top_group=name)
        for sx in (-1, 1):
            for sy in (-1, 1):
                lx = cx + sx * (hx - LEG)
                ly = cy + sy * (hy - LEG)
                box(name + "_frame", "desk", (lx - LEG / 2, ly - LEG / 2, 0.0),
                    (lx + LEG / 2, ly + LEG / 2, DESK_TOP_Z - DESK_TOP_THICKNESS), skip=("bottom", "top"))
    box("partition", "partition", *PARTITION, skip=("bottom",))

    here = os.path.dirname(os.path.abspath(__file__))
    with open(os.path.join(here, "office.obj"), "w") as f:
        f.write("# Small office for ilp, written by data/make_office.py (metres, z up).\n")
        f.write("mtllib office.mtl\n")
        for p in vertices:
            f.write("v %.4f %.4f %.4f\n" % p)
        for group, material, quads in groups:
            f.write("g %s\nusemtl %s\n" % (group, material))
            for ids in quads:
                f.write("f %d %d %d %d\n" % tuple(ids))
    with open(os.path.join(here, "office.mtl"), "w") as f:
        f.write("# Default reflectances (Kd); configs/office.yaml may override them per surface.\n")
        for name, kd in (("floor", (0.3, 0.3, 0.3)), ("ceiling", (0.8, 0.8, 0.8)), ("wall", (0.6, 0.6, 0.6)),
                         ("desk", (0.45, 0.45, 0.45)), ("partition", (0.5, 0.5, 0.5))):
            f.write("newmtl %s\nKd %.3f %.3f %.3f\n\n" % ((name,) + kd))


if __name__ == "__main__":
    main()
