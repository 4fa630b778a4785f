#!/usr/bin/env python3
"""Writes data/floor.obj and data/floor.mtl: one office floor of seven rooms for the
building job configs/floor.yaml (docs/building.md).

    python3 scripts/make_floor.py [--out DIR]     # default: the repository's data/

Plan (x east, y north, z up, metres; ceilings 3.0 m; walls 0.1 m thick between rooms):

    y 10 +---------+---------+--------+
         | storage |  copy   | toilet |
    y  7 +---------+--D------+--D-----+---------------------+
         D corridor (18.2 x 1.8 m)            D             |
    y  5 +---D-----+-----D---+-----------DD---+-------------+
         | office_1          | office_2       | meeting     |
    y  0 +-------------------+----------------+-------------+
         x 0                 6.1              12.2          18.2

Every room is a box of its own surfaces, named after it: <room>_floor (faces up),
<room>_ceiling (down), <room>_walls (into the room), <room>_door (the closed door
leaves in its walls), and furniture: <room>_desks (the desk and table tops) and
<room>_furniture (their undersides and edges; legs are left out). Room faces point into their room, so a room's light
reaches another only through an opening. The meeting room's door is open (a hole
through both wall faces, lined by meeting_reveal): light passes between it and the
corridor there, which the job couples (rooms[].coupled_with). Every other door is
closed: a door leaf in each face of the wall.

Deterministic and small (218 triangles); the output is committed, and running
the script again rewrites the same bytes.
"""
import argparse
import os

H = 3.0          # ceiling height
DOOR_W = 1.0     # door width
DOOR_H = 2.1
T = 0.1          # wall thickness between rooms

# name: (x0, y0, x1, y1)
ROOMS = {
    "office_1": (0.0, 0.0, 6.0, 5.0),
    "office_2": (6.1, 0.0, 12.1, 5.0),
    "meeting": (12.2, 0.0, 18.2, 5.0),
    "corridor": (0.0, 5.1, 18.2, 6.9),
    "storage": (0.0, 7.0, 4.0, 10.0),
    "copy": (4.1, 7.0, 8.1, 10.0),
    "toilet": (8.2, 7.0, 11.2, 10.0),
}
# Doors between a room and the corridor: (room, x of the door's west jamb, open).
DOORS = [
    ("office_1", 1.0, False),
    ("office_2", 7.0, False),
    ("meeting", 12.7, True),
    ("storage", 3.0, False),
    ("copy", 5.0, False),
    ("toilet", 10.0, False),
]
# Desks and tables: (room, x0, y0, x1, y1, top z).
DESKS = [
    ("office_1", 1.0, 1.5, 2.6, 2.3, 0.75),
    ("office_1", 3.4, 1.5, 5.0, 2.3, 0.75),
    ("office_2", 7.1, 1.5, 8.7, 2.3, 0.75),
    ("office_2", 9.5, 1.5, 11.1, 2.3, 0.75),
    ("meeting", 13.7, 1.7, 16.7, 3.1, 0.75),
]
# MTL Kd (the job may override by surface): light finishes within EN 12464-1's useful ranges
# (ceiling 0.7-0.9, walls 0.5-0.8, floor 0.2-0.4)
MATERIALS = {
    "floor": 0.3, "ceiling": 0.85, "walls": 0.7, "door": 0.4, "desks": 0.45, "furniture": 0.4, "reveal": 0.7,
}

vertices = []
index = {}
groups = {}  # name -> (material, [triangles])


def vertex(p):
    key = tuple(round(c, 6) for c in p)
    if key not in index:
        vertices.append(key)
        index[key] = len(vertices)
    return index[key]


def quad(group, material, corners, normal):
    """Adds a planar quad, wound counter-clockwise seen from the side `normal` points to."""
    a, b, c = corners[0], corners[1], corners[2]
    u = [b[i] - a[i] for i in range(3)]
    v = [c[i] - a[i] for i in range(3)]
    n = [u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]]
    if sum(n[i] * normal[i] for i in range(3)) < 0:
        corners = list(reversed(corners))
    ids = [vertex(p) for p in corners]
    groups.setdefault(group, (material, []))[1].append(ids)


def wall(room, axis, at, lo, hi, normal, openings):
    """A vertical wall face of `room` in the plane axis = at (axis "x" or "y"), spanning
    lo..hi along the other horizontal axis and 0..H in z, facing `normal`. openings:
    [(a, b, leaf)] along the wall, each DOOR_H high: a door leaf (closed) or a hole."""
    def point(s, z):
        return (at, s, z) if axis == "x" else (s, at, z)

    def rect(group, material, s0, s1, z0, z1):
        if s1 - s0 < 1e-9:  # a door at the wall's end leaves no piece beside it
            return
        quad(group, material, [point(s0, z0), point(s1, z0), point(s1, z1), point(s0, z1)], normal)

    s = lo
    for a, b, leaf in sorted(openings):
        rect(f"{room}_walls", "walls", s, a, 0.0, H)
        rect(f"{room}_walls", "walls", a, b, DOOR_H, H)
        if leaf:
            rect(f"{room}_door", "door", a, b, 0.0, DOOR_H)
        s = b
    rect(f"{room}_walls", "walls", s, hi, 0.0, H)


def reveal(a, y0, y1):
    """The open door's lining through the wall (x a..a+DOOR_W, y0..y1): jambs, head, sill."""
    b = a + DOOR_W
    quad("meeting_reveal", "reveal", [(a, y0, 0), (a, y1, 0), (a, y1, DOOR_H), (a, y0, DOOR_H)], (1, 0, 0))
    quad("meeting_reveal", "reveal", [(b, y0, 0), (b, y1, 0), (b, y1, DOOR_H), (b, y0, DOOR_H)], (-1, 0, 0))
    quad("meeting_reveal", "reveal", [(a, y0, DOOR_H), (b, y0, DOOR_H), (b, y1, DOOR_H), (a, y1, DOOR_H)], (0, 0, -1))
    quad("meeting_reveal", "reveal", [(a, y0, 0), (b, y0, 0), (b, y1, 0), (a, y1, 0)], (0, 0, 1))


def room_openings(room):
    """Openings in the room's wall toward the corridor, as (a, b, leaf)."""
    return [(x, x + DOOR_W, not is_open) for r, x, is_open in DOORS if r == room]


def corridor_openings(side):
    """Openings in the corridor's south (rooms below) or north wall."""
    below = side == "south"
    out = []
    for r, x, is_open in DOORS:
        if (ROOMS[r][3] <= ROOMS["corridor"][1]) == below:
            out.append((x, x + DOOR_W, not is_open))
    return out


def box_room(room):
    x0, y0, x1, y1 = ROOMS[room]
    quad(f"{room}_floor", "floor", [(x0, y0, 0), (x1, y0, 0), (x1, y1, 0), (x0, y1, 0)], (0, 0, 1))
    quad(f"{room}_ceiling", "ceiling", [(x0, y0, H), (x1, y0, H), (x1, y1, H), (x0, y1, H)], (0, 0, -1))
    corridor = ROOMS["corridor"]
    if room == "corridor":
        south, north = corridor_openings("south"), corridor_openings("north")
    elif y1 <= corridor[1]:  # south of the corridor: doors in its north wall
        south, north = [], room_openings(room)
    else:
        south, north = room_openings(room), []
    wall(room, "y", y0, x0, x1, (0, 1, 0), south)
    wall(room, "y", y1, x0, x1, (0, -1, 0), north)
    wall(room, "x", x0, y0, y1, (1, 0, 0), [])
    wall(room, "x", x1, y0, y1, (-1, 0, 0), [])


def desk(room, x0, y0, x1, y1, z, thickness=0.03):
    """A desk or table top: a slab (its legs left out), the top <room>_desks, its
    underside and edges <room>_furniture, every face pointing out of the slab."""
    b = z - thickness
    quad(f"{room}_desks", "desks", [(x0, y0, z), (x1, y0, z), (x1, y1, z), (x0, y1, z)], (0, 0, 1))
    g = f"{room}_furniture"
    quad(g, "furniture", [(x0, y0, b), (x1, y0, b), (x1, y1, b), (x0, y1, b)], (0, 0, -1))
    quad(g, "furniture", [(x0, y0, b), (x1, y0, b), (x1, y0, z), (x0, y0, z)], (0, -1, 0))
    quad(g, "furniture", [(x0, y1, b), (x1, y1, b), (x1, y1, z), (x0, y1, z)], (0, 1, 0))
    quad(g, "furniture", [(x0, y0, b), (x0, y1, b), (x0, y1, z), (x0, y0, z)], (-1, 0, 0))
    quad(g, "furniture", [(x1, y0, b), (x1, y1, b), (x1, y1, z), (x1, y0, z)], (1, 0, 0))


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    here = os.path.dirname(os.path.abspath(__file__))
    parser.add_argument("--out", default=os.path.join(here, "..", "data"), help="folder for floor.obj and floor.mtl")
    out = parser.parse_args().out
    for room in ROOMS:
        box_room(room)
    meeting_door = [x for r, x, is_open in DOORS if r == "meeting" and is_open]
    for x in meeting_door:
        reveal(x, ROOMS["meeting"][3], ROOMS["corridor"][1])
    for d in DESKS:
        desk(*d)
    os.makedirs(out, exist_ok=True)
    with open(os.path.join(out, "floor.mtl"), "w", newline="\n") as f:
        f.write("# written by scripts/make_floor.py\n")
        for name, kd in MATERIALS.items():
            f.write(f"newmtl {name}\nKd {kd} {kd} {kd}\n")
    with open(os.path.join(out, "floor.obj"), "w", newline="\n") as f:
        f.write("# One office floor of seven rooms, written by scripts/make_floor.py (z up, metres)\n")
        f.write("mtllib floor.mtl\n")
        for v in vertices:
            f.write("v {:g} {:g} {:g}\n".format(*v))
        for name in sorted(groups):
            material, faces = groups[name]
            f.write(f"g {name}\nusemtl {material}\n")
            for ids in faces:
                f.write("f " + " ".join(str(i) for i in ids) + "\n")
    print(f"wrote {os.path.join(out, 'floor.obj')}: {len(vertices)} vertices, "
          f"{sum(len(f) for _, f in groups.values())} quads in {len(groups)} groups")


if __name__ == "__main__":
    main()
