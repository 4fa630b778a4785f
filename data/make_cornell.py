#!/usr/bin/env python3
"""Writes data/cornell.obj and data/cornell.mtl: the Cornell box scaled to a room.

A closed 3 x 3 x 3 m room (z up, metres): white floor, ceiling, back wall (y = 3)
and front wall (y = 0, closed so the room is an enclosure), a red left wall
(x = 0) and a green right wall (x = 3), as in the classic scene seen from y < 0.
Two white boxes stand on the floor where the classic scene has them, rotated by
about -17 and +17 degrees: a short one (0.9 m) near the front right and a tall
one (1.8 m) near the back left. Room faces point into the room and box faces out
of the boxes; the boxes have no bottom face (it would never see light). Reflectances
are the usual Cornell values. Run it again to regenerate; the output is committed
because it is small.
"""
import math
import os

ROOM = (3.0, 3.0, 3.0)
BOX_WIDTH = 0.9
# name: (centre x, centre y, height, rotation about z in degrees), from the classic
# 555-unit scene scaled by 3 / 555 and mirrored so that red is at x = 0.
BOXES = {
    "short_box": (2.0, 0.91, 0.9, -17.0),
    "tall_box": (1.0, 1.9, 1.8, 17.0),
}
MATERIALS = {"white": (0.73, 0.73, 0.73), "red": (0.63, 0.065, 0.05), "green": (0.14, 0.45, 0.091)}

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


def rotated_box(group, material, centre_x, centre_y, height, angle_deg):
    """Four sides and the top of a square box standing on z = 0, faces outwards."""
    c, s = math.cos(math.radians(angle_deg)), math.sin(math.radians(angle_deg))
    h = BOX_WIDTH / 2
    # Footprint corners counter-clockwise seen from above.
    corners = [(centre_x + c * u - s * v, centre_y + s * u + c * v) for u, v in ((-h, -h), (h, -h), (h, h), (-h, h))]
    for (x0, y0), (x1, y1) in zip(corners, corners[1:] + corners[:1]):
        quad(group, material, (x0, y0, 0.0), (x1, y1, 0.0), (x1, y1, height), (x0, y0, height))
    quad(group, material, *[(x, y, height) for x, y in corners])


def main():
    X, Y, Z = ROOM
    # Room: faces point inwards.
    quad("floor", "white", (0, 0, 0), (X, 0, 0), (X, Y, 0), (0, Y, 0))
    quad("ceiling", "white", (0, 0, Z), (0, Y, Z), (X, Y, Z), (X, 0, Z))
    quad("back_wall", "white", (0, Y, 0), (X, Y, 0), (X, Y, Z), (0, Y, Z))    # y = Y
    quad("front_wall", "white", (0, 0, 0), (0, 0, Z), (X, 0, Z), (X, 0, 0))   # y = 0
    quad("left_wall", "red", (0, 0, 0), (0, Y, 0), (0, Y, Z), (0, 0, Z))      # x = 0
    quad("right_wall", "green", (X, 0, 0), (X, 0, Z), (X, Y, Z), (X, Y, 0))   # x = X
    for name, (cx, cy, height, angle_deg) in BOXES.items():
        rotated_box(name, "white", cx, cy, height, angle_deg)

    here = os.path.dirname(os.path.abspath(__file__))
    with open(os.path.join(here, "cornell.obj"), "w") as f:
        f.write("# Cornell box room for ilp, written by data/make_cornell.py (metres, z up).\n")
        f.write("mtllib cornell.mtl\n")
        for p in vertices:
            f.write("v %.4f %.4f %.4f\n" % p)
        for group, material, quads in groups:
            f.write("g %s\nusemtl %s\n" % (group, material))
            for ids in quads:
                f.write("f %d %d %d %d\n" % tuple(ids))
    with open(os.path.join(here, "cornell.mtl"), "w") as f:
        f.write("# The Cornell box's reflectances (Kd); configs/cornell.yaml may override them per surface.\n")
        for name, kd in MATERIALS.items():
            f.write("newmtl %s\nKd %.3f %.3f %.3f\n\n" % ((name,) + kd))


if __name__ == "__main__":
    main()
