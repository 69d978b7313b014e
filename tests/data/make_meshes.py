#!/usr/bin/env python3
"""Writes the small Gmsh 4.1 ASCII meshes the tests use (run from this directory).

patch5.msh     distorted 5-element Q8 patch on r in [10, 20], z in [0, 10]; every boundary
               node is its own physical point group "b<k>" so a test can prescribe a field.
inverted.msh   one Q8 element numbered clockwise (must be rejected).
degenerate.msh one Q8 element with two coincident corners (must be rejected).
no_elements.msh nodes but no 8-node quadrilateral (must be rejected).
dba/thick_sphere.msh a quarter meridian of a thick sphere (a = 100, b = 200 mm), 10 x 8 Q8;
               lines "inner", "outer", "bottom" (z = 0) and "axis" (r = 0).
"""
import math

def write(name, nodes, quads, lines=(), points=(), names=()):
    """nodes: {tag: (x, y)}; quads: [(tag, [8 node tags])]; lines: [(phys, tag, [3 tags])];
    points: [(phys, tag, node)]; names: [(dim, phys, name)]."""
    out = ["$MeshFormat", "4.1 0 8", "$EndMeshFormat"]
    if names:
        out += ["$PhysicalNames", str(len(names))]
        out += [f'{d} {p} "{n}"' for d, p, n in names]
        out += ["$EndPhysicalNames"]
    # one entity per physical point / line group, one surface entity
    pt_ents = [(i + 1, phys, nodes[n]) for i, (phys, _, n) in enumerate(points)]
    line_phys = sorted({p for p, _, _ in lines})
    out += ["$Entities", f"{len(pt_ents)} {len(line_phys)} 1 0"]
    for tag, phys, (x, y) in pt_ents:
        out.append(f"{tag} {x} {y} 0 1 {phys}")
    for i, phys in enumerate(line_phys):
        out.append(f"{i + 1} 0 0 0 1 1 0 1 {phys} 0")
    out.append("1 0 0 0 1 1 0 0 0")
    out.append("$EndEntities")
    tags = sorted(nodes)
    out += ["$Nodes", f"1 {len(tags)} {min(tags)} {max(tags)}", f"2 1 0 {len(tags)}"]
    out += [str(t) for t in tags]
    out += [f"{nodes[t][0]!r} {nodes[t][1]!r} 0" for t in tags]
    out.append("$EndNodes")
    blocks = []
    for tag, phys, n in pt_ents:
        el = [e for e in points if e[0] == phys][0]
        blocks.append((0, tag, 15, [(el[1], [el[2]])]))
    for i, phys in enumerate(line_phys):
        blocks.append((1, i + 1, 8, [(t, ns) for p, t, ns in lines if p == phys]))
    if quads:
        blocks.append((2, 1, 16, quads))
    all_tags = [t for b in blocks for t, _ in b[3]]
    out += ["$Elements", f"{len(blocks)} {len(all_tags)} {min(all_tags, default=0)} {max(all_tags, default=0)}"]
    for dim, ent, ty, els in blocks:
        out.append(f"{dim} {ent} {ty} {len(els)}")
        out += [" ".join(str(v) for v in [t] + list(ns)) for t, ns in els]
    out.append("$EndElements")
    with open(name, "w") as f:
        f.write("\n".join(out) + "\n")


def patch():
    corner = {1: (10.0, 0.0), 2: (20.0, 0.0), 3: (20.0, 10.0), 4: (10.0, 10.0),   # outer square
              5: (12.0, 2.0), 6: (17.0, 3.0), 7: (16.0, 7.0), 8: (13.0, 8.0)}     # skewed inner quad
    nodes = dict(corner)
    mid = {}
    def m(a, b):
        key = (min(a, b), max(a, b))
        if key not in mid:
            t = 100 + len(mid)
            (xa, ya), (xb, yb) = corner[a], corner[b]
            nodes[t] = ((xa + xb) / 2, (ya + yb) / 2)
            mid[key] = t
        return mid[key]
    quads_c = [(5, 6, 7, 8), (1, 2, 6, 5), (2, 3, 7, 6), (3, 4, 8, 7), (4, 1, 5, 8)]
    quads = []
    for k, (a, b, c, d) in enumerate(quads_c):
        quads.append((1000 + k, [a, b, c, d, m(a, b), m(b, c), m(c, d), m(d, a)]))
    boundary = [1, 2, 3, 4, m(1, 2), m(2, 3), m(3, 4), m(4, 1)]
    points = [(k + 1, 2000 + k, n) for k, n in enumerate(boundary)]
    names = [(0, k + 1, f"b{k + 1}") for k in range(len(boundary))]
    write("patch5.msh", nodes, quads, points=points, names=names)


def sphere(name, a, b, nr, nt):
    """A quarter meridian a <= R <= b, nr x nt Q8 (R, then the angle from the equator)."""
    # nodes on a (2nr+1) x (2nt+1) grid in (radius, polar angle from the z axis)
    nodes = {}
    def tag(i, j): return 1 + i + (2*nr+1)*j
    for j in range(2*nt+1):
        th = 0.5*math.pi*j/(2*nt)
        for i in range(2*nr+1):
            R = a + (b-a)*i/(2*nr)
            if (i % 2 == 1) and (j % 2 == 1):
                continue
            # polar angle from the equator (z = 0) to the pole (r = 0)
            nodes[tag(i, j)] = (R*math.cos(th), R*math.sin(th))
    quads = []
    t = 1000
    for j in range(nt):
        for i in range(nr):
            i0, j0 = 2*i, 2*j
            c = [tag(i0, j0), tag(i0+2, j0), tag(i0+2, j0+2), tag(i0, j0+2)]
            m = [tag(i0+1, j0), tag(i0+2, j0+1), tag(i0+1, j0+2), tag(i0, j0+1)]
            quads.append((t, c + m)); t += 1
    lines = []
    for j in range(nt):   # inner (i = 0) and outer (i = 2nr) arcs
        lines.append((1, t, [tag(0, 2*j+2), tag(0, 2*j), tag(0, 2*j+1)])); t += 1
        lines.append((2, t, [tag(2*nr, 2*j), tag(2*nr, 2*j+2), tag(2*nr, 2*j+1)])); t += 1
    for i in range(nr):   # equator z = 0 and the axis r = 0
        lines.append((3, t, [tag(2*i, 0), tag(2*i+2, 0), tag(2*i+1, 0)])); t += 1
        lines.append((4, t, [tag(2*i+2, 2*nt), tag(2*i, 2*nt), tag(2*i+1, 2*nt)])); t += 1
    write(name, nodes, quads, lines, (), [(1, 1, "inner"), (1, 2, "outer"), (1, 3, "bottom"), (1, 4, "axis")])

def one(name, conn, coords):
    write(name, coords, [(1, conn)])


if __name__ == "__main__":
    patch()
    sq = {1: (1.0, 0.0), 2: (2.0, 0.0), 3: (2.0, 1.0), 4: (1.0, 1.0),
          5: (1.5, 0.0), 6: (2.0, 0.5), 7: (1.5, 1.0), 8: (1.0, 0.5)}
    one("inverted.msh", [1, 4, 3, 2, 8, 7, 6, 5], sq)
    deg = dict(sq)
    deg[3] = deg[2]
    deg[6] = deg[2]
    one("degenerate.msh", [1, 2, 3, 4, 5, 6, 7, 8], deg)
    write("no_elements.msh", sq, [], points=[(1, 1, 1)], names=[(0, 1, "p")])
    sphere("dba/thick_sphere.msh", 100.0, 200.0, 10, 8)
