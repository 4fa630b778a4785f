#!/usr/bin/env python3
"""Writes data/cornell.obj and data/cornell.mtl: the Cornell box scaled to a room.

A closed 3 x 3 x 3 m room (z up, metres): white floor, ceiling, back wall (y = 3)
and front wall (y = 0, closed so the room is an enclosure), a red left wall
(x = 0) and a green right wall (x = 3), as in the classic scene seen from y < 0.
Two white boxes stand on the floor where the classic scene has them, rotated by
about -17 and +17 degrees: a short one (0.9 m) near the front right and a tall
one (1.8 m) near the back left. Room faces point into the room and box faces out
of the boxes; the boxes have no bottom face (it would never see light), and the
floor has holes exactly at the box footprints, so no floor patch hides under a box
(it would get no light and spoil the floor's minimum and uniformity). Reflectances
are the usual Cornell values. Run it again to regenerate; the output is committed
because it is small.

The floor is a grid of FLOOR_CELLS x FLOOR_CELLS square cells (small enough that the
mesher keeps each cell triangle as one patch, as dense as the old single-quad floor
meshed at max_patch_edge_m = 0.2); cells crossing a footprint are cut into convex
pieces outside it; pieces with a neighbour's vertex inside an edge are split into
triangles that include it, so faces meet vertex to vertex (no T-junctions). Every
floor face is convex and counter-clockwise seen from above.
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
# Floor cells per side: 3 m / 22 = 0.136 m, so a cell's diagonal (0.193 m) stays below
# configs/cornell.yaml's max_patch_edge_m.
FLOOR_CELLS = 22
MATERIALS = {"white": (0.73, 0.73, 0.73), "red": (0.63, 0.065, 0.05), "green": (0.14, 0.45, 0.091)}

vertices = []  # (x, y, z, exact): exact vertices are written in full precision
groups = []  # (group, material, [faces as vertex index lists])
shared_vertices = {}  # exact vertices by position, to share them between faces


def vertex(p, exact=False):
    """Index of a new vertex at p, or with exact=True, of the one exact vertex at p."""
    if exact:
        if p not in shared_vertices:
            vertices.append(tuple(p) + (True,))
            shared_vertices[p] = len(vertices)
        return shared_vertices[p]
    vertices.append(tuple(p) + (False,))
    return len(vertices)


def face(group, material, ids):
    for g in groups:
        if g[0] == group:
            g[2].append(ids)
            return
    groups.append((group, material, [ids]))


def quad(group, material, a, b, c, d):
    """Adds quad a-b-c-d, counter-clockwise seen from its front."""
    face(group, material, [vertex(p) for p in (a, b, c, d)])


def footprint(centre_x, centre_y, angle_deg):
    """A box's footprint corners, counter-clockwise seen from above."""
    c, s = math.cos(math.radians(angle_deg)), math.sin(math.radians(angle_deg))
    h = BOX_WIDTH / 2
    return [(centre_x + c * u - s * v, centre_y + s * u + c * v) for u, v in ((-h, -h), (h, -h), (h, h), (-h, h))]


def rotated_box(group, material, centre_x, centre_y, height, angle_deg):
    """Four sides and the top of a square box standing on z = 0, faces outwards."""
    corners = footprint(centre_x, centre_y, angle_deg)
    for (x0, y0), (x1, y1) in zip(corners, corners[1:] + corners[:1]):
        quad(group, material, (x0, y0, 0.0), (x1, y1, 0.0), (x1, y1, height), (x0, y0, height))
    quad(group, material, *[(x, y, height) for x, y in corners])


# --- Floor with holes: 2D convex polygons (lists of (x, y), counter-clockwise). ---

def cross(o, a, b):
    return (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0])


def area(poly):
    """Signed area, positive for counter-clockwise."""
    return 0.5 * sum(x0 * y1 - x1 * y0 for (x0, y0), (x1, y1) in zip(poly, poly[1:] + poly[:1]))


def clip(poly, a, b):
    """The part of convex poly on the left of (or on) the directed line a -> b (Sutherland-Hodgman)."""
    out = []
    for p, q in zip(poly, poly[1:] + poly[:1]):
        sp, sq = cross(a, b, p), cross(a, b, q)
        if sp >= 0:
            out.append(p)
        if (sp > 0 and sq < 0) or (sp < 0 and sq > 0):
            t = sp / (sp - sq)
            out.append((p[0] + t * (q[0] - p[0]), p[1] + t * (q[1] - p[1])))
    return tidy(out)


def tidy(poly, eps=1e-12):
    """Drops repeated and collinear vertices; returns [] for a polygon without area."""
    changed = True
    while changed and len(poly) >= 3:
        changed = False
        for k in range(len(poly)):
            prev, cur, nxt = poly[k - 1], poly[k], poly[(k + 1) % len(poly)]
            if abs(cross(prev, cur, nxt)) <= eps * max(1.0, math.dist(prev, nxt)):
                del poly[k]
                changed = True
                break
    return poly if len(poly) >= 3 and area(poly) > 0 else []


def subtract(poly, hole):
    """Convex pieces of convex poly outside convex hole (both counter-clockwise): the
    piece outside hole edge k but inside edges 0..k-1, for each k; they do not overlap."""
    xs, ys = [p[0] for p in hole], [p[1] for p in hole]
    if (max(p[0] for p in poly) <= min(xs) or min(p[0] for p in poly) >= max(xs) or
            max(p[1] for p in poly) <= min(ys) or min(p[1] for p in poly) >= max(ys)):
        return [poly]
    pieces, rest = [], poly
    for a, b in zip(hole, hole[1:] + hole[:1]):
        outside = clip(rest, b, a)
        if outside:
            pieces.append(outside)
        rest = clip(rest, a, b)
        if not rest:
            break
    return pieces


def overlap_area(p, q):
    """Area of the intersection of two convex counter-clockwise polygons."""
    for a, b in zip(q, q[1:] + q[:1]):
        p = clip(p, a, b)
        if not p:
            return 0.0
    return area(p)


def without_t_junctions(pieces):
    """Adds to each piece the vertices of other pieces that lie inside its edges, so that
    neighbouring floor faces meet vertex to vertex: a T-junction can leave a crack that
    lets a ray out of the room."""
    points = sorted(set(v for p in pieces for v in p))
    out = []
    for p in pieces:
        q = []
        for a, b in zip(p, p[1:] + p[:1]):
            q.append(a)
            d = (b[0] - a[0], b[1] - a[1])
            length2 = d[0] ** 2 + d[1] ** 2
            along = lambda v: (v[0] - a[0]) * d[0] + (v[1] - a[1]) * d[1]
            on = [v for v in points if abs(cross(a, b, v)) <= 1e-12 * math.sqrt(length2) and 0 < along(v) < length2]
            q += sorted(on, key=along)
        out.append(q)
    return out


def convex_faces(poly):
    """poly itself if it is strictly convex, else (it has vertices inside straight edges)
    triangles of it without degenerate ones: ears cut at strictly convex vertices,
    never leaving a remainder without area."""
    def corner(p, k):
        return cross(p[k - 1], p[k], p[(k + 1) % len(p)])
    if all(corner(poly, k) > 1e-13 for k in range(len(poly))):
        return [poly]
    poly, faces = list(poly), []
    while len(poly) > 3:
        for k in range(len(poly)):
            rest = poly[:k] + poly[k + 1:]
            if corner(poly, k) > 1e-13 and any(corner(rest, j) > 1e-13 for j in range(len(rest))):
                faces.append([poly[k - 1], poly[k], poly[(k + 1) % len(poly)]])
                poly = rest
                break
        else:
            raise AssertionError("cannot triangulate %r" % poly)
    assert corner(poly, 0) > 1e-13, poly
    return faces + [poly]


def floor_pieces(holes):
    """Convex pieces covering the room's floor square minus the holes, checked."""
    X, Y = ROOM[0], ROOM[1]
    n = FLOOR_CELLS
    xs = [X * i / n for i in range(n + 1)]
    ys = [Y * j / n for j in range(n + 1)]
    pieces = []
    for i in range(n):
        for j in range(n):
            cell = [[(xs[i], ys[j]), (xs[i + 1], ys[j]), (xs[i + 1], ys[j + 1]), (xs[i], ys[j + 1])]]
            for hole in holes:
                cell = [q for p in cell for q in subtract(p, hole)]
            pieces += cell
    # A hole corner found as the crossing of two lines may be off by round-off: use the
    # corner itself, so that the floor meets the box at the box's own vertices.
    corners = [c for hole in holes for c in hole]
    pieces = [[next((c for c in corners if math.dist(c, v) < 1e-9), v) for v in p] for p in pieces]
    pieces = [f for p in without_t_junctions(pieces) for f in convex_faces(p)]

    # Checks: convex and counter-clockwise, inside the square, outside the holes, no
    # two pieces overlapping, and the area is the square's minus the holes'.
    for p in pieces:
        assert all(cross(p[k - 2], p[k - 1], p[k]) > 0 for k in range(len(p))), p
        assert all(0 <= x <= X and 0 <= y <= Y for x, y in p), p
        for hole in holes:
            assert abs(overlap_area(p, hole)) < 1e-12, (p, hole)
    boxes = [(min(x for x, _ in p), max(x for x, _ in p), min(y for _, y in p), max(y for _, y in p)) for p in pieces]
    for k, (p, bp) in enumerate(zip(pieces, boxes)):
        for q, bq in zip(pieces[k + 1:], boxes[k + 1:]):
            if bp[1] > bq[0] and bq[1] > bp[0] and bp[3] > bq[2] and bq[3] > bp[2]:
                assert abs(overlap_area(p, q)) < 1e-12, (p, q)
    total = sum(area(p) for p in pieces)
    expected = X * Y - sum(area(h) for h in holes)
    assert abs(total - expected) < 1e-9, (total, expected)
    return pieces, total, expected


def main():
    X, Y, Z = ROOM
    # Room: faces point inwards. The floor (normal +z) has holes at the box footprints,
    # taken as written to the OBJ (4 decimals) so that they meet the box sides exactly.
    holes = [[(round(x, 4), round(y, 4)) for x, y in footprint(cx, cy, a)] for cx, cy, _, a in BOXES.values()]
    for cx, cy, _, a in BOXES.values():  # the rounded corners are the box's written ones
        assert all("%.4f %.4f" % (x, y) == "%.4f %.4f" % (round(x, 4), round(y, 4)) for x, y in footprint(cx, cy, a))
    pieces, total, expected = floor_pieces(holes)
    for p in pieces:
        face("floor", "white", [vertex((x, y, 0.0), exact=True) for x, y in p])
    print("floor: %d convex faces (%d triangles), area %.12f m2 = 9 m2 - footprints %.12f m2 (difference %.1e); "
          "smallest face %.2e m2" % (len(pieces), sum(len(p) - 2 for p in pieces), total, X * Y - expected,
                                     total - expected, min(area(p) for p in pieces)))
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
        for x, y, z, exact in vertices:
            if exact:  # floor vertices: shortest text that reads back as the same double
                f.write("v %r %r %r\n" % (x, y, z))
            else:
                f.write("v %.4f %.4f %.4f\n" % (x, y, z))
        for group, material, faces in groups:
            f.write("g %s\nusemtl %s\n" % (group, material))
            for ids in faces:
                f.write("f %s\n" % " ".join(str(k) for k in ids))
    with open(os.path.join(here, "cornell.mtl"), "w") as f:
        f.write("# The Cornell box's reflectances (Kd); configs/cornell.yaml may override them per surface.\n")
        for name, kd in MATERIALS.items():
            f.write("newmtl %s\nKd %.3f %.3f %.3f\n\n" % ((name,) + kd))


if __name__ == "__main__":
    main()
