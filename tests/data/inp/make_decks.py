#!/usr/bin/env python3
"""Writes the CalculiX/Abaqus example decks of tests/data/inp (run from anywhere).

All are axisymmetric CAX8 models (spun_disc CAX8R) in mm, N, MPa, degC, written the way an engineer writes them
by hand or exports them from a pre-processor: nodes and elements (one in an *INCLUDE file),
sets, element-face surfaces, materials, contact pairs and steps.

lame.inp          thick cylinder a = 100, b = 150 under 100 MPa inside, ends held axially
                  (plane strain), elastic, small strain. Mesh in lame_mesh.inc (*INCLUDE).
push_out.inp      a ring r 60..80 shrunk on a rigid shaft (0.05 mm interference), then pushed
                  0.1 mm along it: node-to-surface contact with Coulomb friction mu = 0.2.
shrink_fit.inp    tube r 50..60.05 shrunk into a ring r 60..80 (0.05 mm radial interference),
                  face-to-face penalty contact; step 2 adds 50 MPa in the bore through an
                  *AMPLITUDE (full at half the step, then held). Elastic, small strain.
adjusted_fit.inp  a tapered tube (outer r 59.97 at z = 0 to 60.03 at z = 10) in a ring r 60..80:
                  ADJUST=0.01 moves the tube's outer nodes within 0.01 mm of the ring's bore,
                  and the overclosed ones, onto it; the rest keep their gaps. Then 50 MPa in
                  the bore. Face-to-face penalty contact, elastic, small strain.
hertz.inp         the tip of a sphere R = 50 pushed 0.05 mm into a block, both elastic steel,
                  face-to-face penalty contact, small strain.
spun_disc.inp     an annular disc r 5..100, 10 thick, of CalculiX's reduced CAX8R (2 x 2 Gauss points),
                  five elements across, spun at 1000 rad/s (*DLOAD CENTRIF) with 10 MPa on its
                  top face and its bottom face held axially: the coarse mesh across the bore's
                  steep hoop-stress gradient is where reduced and full integration differ.
kinematic_cylinder.inp  thick cylinder a = 100, b = 150 of 10 CAX8R across, ends held axially (plane
                  strain), linear kinematic hardening (*PLASTIC, HARDENING=KINEMATIC: yield 100 MPa,
                  slope 10 GPa): 70 MPa inside (step 1; past the bore's yield at about 32 MPa),
                  back to 0 (step 2; the bore yields in reverse, as it would not with isotropic
                  hardening), and 70 MPa again (step 3). NLGEOM: CalculiX 2.20's small-strain
                  kinematic hardening softens while loading (200 to 49 MPa over 1 % uniaxial strain).
small_bellows.inp one smooth convolution of two 0.5 mm plies (r 50..58, 2 x 80 elements each), J2 plasticity with a
                  three-point hardening table, heated to 200 degC with 1 MPa inside (step 1),
                  then compressed 4 mm axially (step 2), NLGEOM, contact between the plies.

Each deck has *NODE PRINT requests for CalculiX (RF totals of the set whose reaction is
compared, U of the probe nodes); scripts/compare-calculix.sh reads them.
"""

import math
import os

HERE = os.path.dirname(os.path.abspath(__file__))


class Mesh:
    def __init__(self):
        self.nodes = {}  # id -> (r, z)
        self.elements = []  # (id, [8 node ids])

    def block(self, ni, nj, position):
        """A structured Q8 block: ni x nj elements, position(I, J) -> (r, z) on the node grid
        I in 0..2ni, J in 0..2nj (I across, J along; I and J increasing counter-clockwise).
        Returns (grid of node ids, list of element rows [j][i])."""
        grid = {}
        for J in range(2 * nj + 1):
            for I in range(2 * ni + 1):
                if I % 2 == 1 and J % 2 == 1:
                    continue
                nid = len(self.nodes) + 1
                self.nodes[nid] = position(I, J)
                grid[I, J] = nid
        rows = []
        for j in range(nj):
            row = []
            for i in range(ni):
                I, J = 2 * i, 2 * j
                conn = [grid[I, J], grid[I + 2, J], grid[I + 2, J + 2], grid[I, J + 2],
                        grid[I + 1, J], grid[I + 2, J + 1], grid[I + 1, J + 2], grid[I, J + 1]]
                eid = len(self.elements) + 1
                self.elements.append((eid, conn))
                row.append(eid)
            rows.append(row)
        return grid, rows

    def node_lines(self):
        out = ["*NODE"]
        out += [f"{n}, {r:.10g}, {z:.10g}" for n, (r, z) in sorted(self.nodes.items())]
        return out

    def element_lines(self, ids, elset, kind="CAX8"):
        out = [f"*ELEMENT, TYPE={kind}, ELSET={elset}"]
        conn = dict(self.elements)
        out += [f"{e}, " + ", ".join(str(n) for n in conn[e]) for e in ids]
        return out


def listing(keyword, ids, per_line=12):
    out = [keyword]
    ids = list(ids)
    for k in range(0, len(ids), per_line):
        out.append(", ".join(str(i) for i in ids[k:k + per_line]))
    return out


def side(grid, ni, nj, which):
    """Node ids along one side of a block's node grid."""
    if which == "left":
        return [grid[0, J] for J in range(2 * nj + 1)]
    if which == "right":
        return [grid[2 * ni, J] for J in range(2 * nj + 1)]
    if which == "bottom":
        return [grid[I, 0] for I in range(2 * ni + 1)]
    return [grid[I, 2 * nj] for I in range(2 * ni + 1)]


def surface(name, faces):
    return [f"*SURFACE, NAME={name}, TYPE=ELEMENT"] + [f"{e}, S{s}" for e, s in faces]


def stations(fine, n_fine, total, n_coarse):
    """n_fine equal steps up to `fine`, then n_coarse growing geometrically to `total`."""
    h = fine / n_fine
    out = [k * h for k in range(n_fine + 1)]
    lo, hi = 1.0, 2.0
    for _ in range(200):
        q = 0.5 * (lo + hi)
        if sum(h * q ** k for k in range(1, n_coarse + 1)) > total - fine:
            hi = q
        else:
            lo = q
    x = fine
    for k in range(1, n_coarse + 1):
        x += h * q ** k
        out.append(x)
    out[-1] = total
    return out


def with_mid(s):
    out = [s[0]]
    for a, b in zip(s, s[1:]):
        out += [0.5 * (a + b), b]
    return out


def write(name, lines):
    with open(os.path.join(HERE, name), "w") as f:
        f.write("\n".join(lines) + "\n")


STEEL = ["*MATERIAL, NAME=STEEL", "*ELASTIC", "200000., 0.3"]


def lame():
    a, b, h, ni, nj = 100.0, 150.0, 10.0, 8, 1
    m = Mesh()
    grid, rows = m.block(ni, nj, lambda I, J: (a + (b - a) * I / (2 * ni), h * J / (2 * nj)))
    mesh = ["** thick cylinder mesh: 8 x 1 CAX8, r 100..150, z 0..10"] + m.node_lines()
    mesh += m.element_lines([e for r in rows for e in r], "CYLINDER")
    write("lame_mesh.inc", mesh)
    deck = ["*HEADING", "Lame thick cylinder, 100 MPa inside, plane strain (ends held axially)",
            "*INCLUDE, INPUT=lame_mesh.inc",
            "*ELSET, ELSET=ALL, GENERATE", f"1, {ni * nj}, 1"]
    deck += listing("*NSET, NSET=BOTTOM", side(grid, ni, nj, "bottom"))
    deck += listing("*NSET, NSET=TOP", side(grid, ni, nj, "top"))
    deck += ["*NSET, NSET=PROBE", f"{grid[0, 0]}, {grid[2 * ni, 0]}"]
    deck += ["*ELSET, ELSET=INNER", f"{rows[0][0]}"]
    deck += STEEL + ["*SOLID SECTION, ELSET=ALL, MATERIAL=STEEL", "1.",
                     "*BOUNDARY", "BOTTOM, 2, 2",
                     "*STEP", "*STATIC, DIRECT", "1., 1.",
                     "*BOUNDARY", "TOP, 2, 2, 0.",
                     "*DLOAD", "INNER, P4, 100.",
                     "*NODE PRINT, NSET=TOP, TOTALS=ONLY", "RF",
                     "*NODE PRINT, NSET=PROBE", "U",
                     "*NODE FILE", "U", "*EL FILE", "S",
                     "*END STEP"]
    write("lame.inp", deck)


def spun_disc():
    a, b, h, ni, nj = 5.0, 100.0, 10.0, 5, 1
    m = Mesh()
    grid, rows = m.block(ni, nj, lambda I, J: (a + (b - a) * I / (2 * ni), h * J / (2 * nj)))
    elements = [e for r in rows for e in r]
    deck = ["*HEADING", "Annular disc of CAX8R spun at 1000 rad/s, 10 MPa on its top face"] + m.node_lines()
    deck += m.element_lines(elements, "DISC", kind="CAX8R")
    deck += listing("*NSET, NSET=BOTTOM", side(grid, ni, nj, "bottom"))
    deck += ["*ELSET, ELSET=TOPS"] + [", ".join(str(e) for e in elements)]
    deck += STEEL + ["*DENSITY", "7.85e-9", "*SOLID SECTION, ELSET=DISC, MATERIAL=STEEL",
                     "*BOUNDARY", "BOTTOM, 2, 2",
                     "*STEP", "*STATIC, DIRECT", "1., 1.",
                     "*DLOAD", "DISC, CENTRIF, 1.e6, 0., 0., 0., 0., 1., 0.",
                     "TOPS, P3, 10.",
                     "*NODE PRINT, NSET=BOTTOM, TOTALS=ONLY", "RF",
                     "*NODE PRINT, NSET=BOTTOM", "U",
                     "*NODE FILE", "U", "*EL FILE", "S",
                     "*END STEP"]
    write("spun_disc.inp", deck)


def kinematic_cylinder():
    a, b, h, ni, nj = 100.0, 150.0, 10.0, 10, 1
    m = Mesh()
    grid, rows = m.block(ni, nj, lambda I, J: (a + (b - a) * I / (2 * ni), h * J / (2 * nj)))
    elements = [e for r in rows for e in r]
    deck = ["*HEADING", "Thick cylinder with linear kinematic hardening: 70 MPa inside, off, on again"] + m.node_lines()
    deck += m.element_lines(elements, "CYLINDER", kind="CAX8R")
    deck += listing("*NSET, NSET=BOTTOM", side(grid, ni, nj, "bottom"))
    deck += listing("*NSET, NSET=TOP", side(grid, ni, nj, "top"))
    deck += ["*NSET, NSET=PROBE", f"{grid[0, 0]}, {grid[ni, 0]}, {grid[2 * ni, 0]}"]
    deck += ["*ELSET, ELSET=INNER", f"{rows[0][0]}"]
    deck += ["*MATERIAL, NAME=STEEL", "*ELASTIC", "200000., 0.3",
             "*PLASTIC, HARDENING=KINEMATIC", "100., 0.", "600., 0.05",
             "*SOLID SECTION, ELSET=CYLINDER, MATERIAL=STEEL",
             "*BOUNDARY", "BOTTOM, 2, 2"]
    for name, pressure in (("load", 70.0), ("unload", 0.0), ("reload", 70.0)):
        held = ["*BOUNDARY", "TOP, 2, 2, 0."] if name == "load" else []
        deck += ["*STEP, NLGEOM, INC=100", f"** {name}", "*STATIC, DIRECT", "0.1, 1."] + held + [
                 "*DLOAD", f"INNER, P4, {pressure}",
                 "*NODE PRINT, NSET=TOP, TOTALS=ONLY", "RF",
                 "*NODE PRINT, NSET=PROBE", "U",
                 "*NODE FILE", "U", "*EL FILE", "S, PEEQ",
                 "*END STEP"]
    write("kinematic_cylinder.inp", deck)


def fit_mesh(m, gi, ri, go, ro, nj):
    """The fit decks' nodes, the tube's (4 across) and the ring's (6 across) elements, ALL and
    the common bottom face BOTTOM."""
    return (m.node_lines() + m.element_lines([e for r in ri for e in r], "TUBE")
            + m.element_lines([e for r in ro for e in r], "RING") + ["*ELSET, ELSET=ALL", "TUBE, RING"]
            + listing("*NSET, NSET=BOTTOM", side(gi, 4, nj, "bottom") + side(go, 6, nj, "bottom")))


def fit_surfaces(ri, ro):
    """The fit decks' contact surfaces (the tube's outside, the ring's bore) and the tube's bore."""
    return (surface("TUBE_OUT", [(r[-1], 2) for r in ri]) + surface("RING_IN", [(r[0], 4) for r in ro])
            + listing("*ELSET, ELSET=TUBE_INNER", [r[0] for r in ri]))


def fit_contact(parameters):
    """Steel for all, and face-to-face penalty contact of the tube's outside on the ring's bore
    (extra *CONTACT PAIR `parameters`)."""
    return STEEL + ["*SOLID SECTION, ELSET=ALL, MATERIAL=STEEL",
                    "*SURFACE INTERACTION, NAME=FIT",
                    "*SURFACE BEHAVIOR, PRESSURE-OVERCLOSURE=LINEAR", "1.e6",
                    f"*CONTACT PAIR, INTERACTION=FIT, TYPE=SURFACE TO SURFACE{parameters}", "TUBE_OUT, RING_IN"]


def shrink_fit():
    m = Mesh()
    h, nj = 10.0, 2
    gi, ri = m.block(4, nj, lambda I, J: (50.0 + 10.05 * I / 8, h * J / (2 * nj)))
    go, ro = m.block(6, nj, lambda I, J: (60.0 + 20.0 * I / 12, h * J / (2 * nj)))
    deck = ["*HEADING", "Shrink fit: tube r 50..60.05 in ring r 60..80, then 50 MPa in the bore"]
    deck += fit_mesh(m, gi, ri, go, ro, nj)
    deck += listing("*NSET, NSET=TUBE_TOP", side(gi, 4, nj, "top"))
    deck += listing("*NSET, NSET=RING_TOP", side(go, 6, nj, "top"))
    deck += ["*NSET, NSET=PROBE", f"{gi[0, 0]}, {go[0, 0]}, {go[12, 0]}"]
    deck += fit_surfaces(ri, ro)
    deck += fit_contact("") + ["*AMPLITUDE, NAME=UP_AND_HOLD", "0., 0., 0.5, 1., 1., 1.",
                     "*BOUNDARY", "BOTTOM, 2, 2",
                     "*STEP", "*STATIC, DIRECT", "1., 1.",
                     "*BOUNDARY", "TUBE_TOP, 2, 2, 0.", "RING_TOP, 2, 2, 0.",
                     "*NODE PRINT, NSET=RING_TOP, TOTALS=ONLY", "RF",
                     "*NODE PRINT, NSET=PROBE", "U",
                     "*NODE FILE", "U", "*EL FILE", "S",
                     "*END STEP",
                     "*STEP", "*STATIC, DIRECT", "0.25, 1.",
                     "*DLOAD, AMPLITUDE=UP_AND_HOLD", "TUBE_INNER, P4, 50.",
                     "*NODE PRINT, NSET=RING_TOP, TOTALS=ONLY", "RF",
                     "*NODE PRINT, NSET=PROBE", "U",
                     "*NODE FILE", "U", "*EL FILE", "S",
                     "*END STEP"]
    write("shrink_fit.inp", deck)


def adjusted_fit():
    m = Mesh()
    h, nj = 10.0, 4
    outer = lambda z: 59.97 + 0.06 * z / h
    gi, ri = m.block(4, nj, lambda I, J: (50.0 + (outer(h * J / (2 * nj)) - 50.0) * I / 8, h * J / (2 * nj)))
    go, ro = m.block(6, nj, lambda I, J: (60.0 + 20.0 * I / 12, h * J / (2 * nj)))
    deck = ["*HEADING", "Adjusted fit: tapered tube (outer r 59.97..60.03) in ring r 60..80, ADJUST=0.01, then 50 MPa"]
    deck += fit_mesh(m, gi, ri, go, ro, nj)
    deck += listing("*NSET, NSET=TOP", side(gi, 4, nj, "top") + side(go, 6, nj, "top"))
    deck += ["*NSET, NSET=PROBE", f"{gi[0, 0]}, {gi[8, 0]}, {gi[8, 4]}, {gi[8, 8]}, {go[0, 0]}, {go[0, 8]}, {go[12, 0]}"]
    deck += fit_surfaces(ri, ro)
    deck += fit_contact(", ADJUST=0.01") + ["*BOUNDARY", "BOTTOM, 2, 2",
                     "*STEP", "*STATIC, DIRECT", "0.25, 1.",
                     "*BOUNDARY", "TOP, 2, 2, 0.",
                     "*DLOAD", "TUBE_INNER, P4, 50.",
                     "*NODE PRINT, NSET=TOP, TOTALS=ONLY", "RF",
                     "*NODE PRINT, NSET=PROBE", "U",
                     "*NODE FILE", "U", "*EL FILE", "S",
                     "*END STEP"]
    write("adjusted_fit.inp", deck)


def push_out():
    """A ring r 60..80 shrunk on a rigid shaft (the tube r 50..60.05, every node held: 0.05 mm
    radial interference), both 10 mm long; step 1 makes the fit with the ring's faces held
    axially, step 2 pushes the ring 0.1 mm along the shaft by its faces. Node-to-surface penalty
    contact with Coulomb friction mu = 0.2 and a stick slope of 1e5 MPa/mm."""
    m = Mesh()
    h, nj = 10.0, 4
    gi, ri = m.block(2, nj, lambda I, J: (50.0 + 10.05 * I / 4, h * J / (2 * nj)))
    go, ro = m.block(6, nj, lambda I, J: (60.0 + 20.0 * I / 12, h * J / (2 * nj)))
    deck = ["*HEADING", "Push-out: ring r 60..80 shrunk on a rigid shaft r 60.05, pushed 0.1 mm along it, mu = 0.2"]
    deck += m.node_lines()
    deck += m.element_lines([e for r in ri for e in r], "SHAFT")
    deck += m.element_lines([e for r in ro for e in r], "RING")
    deck += ["*ELSET, ELSET=ALL", "SHAFT, RING"]
    shaft_nodes = sorted({n for r in ri for e in r for n in m.elements[e - 1][1]})
    deck += listing("*NSET, NSET=SHAFT_ALL", shaft_nodes)
    deck += listing("*NSET, NSET=RING_FACES", side(go, 6, nj, "bottom") + side(go, 6, nj, "top"))
    deck += ["*NSET, NSET=PROBE", f"{go[0, nj]}, {go[12, 2 * nj]}"]
    deck += surface("SHAFT_OUT", [(r[-1], 2) for r in ri])
    deck += surface("RING_IN", [(r[0], 4) for r in ro])
    deck += STEEL + ["*SOLID SECTION, ELSET=ALL, MATERIAL=STEEL",
                     "*SURFACE INTERACTION, NAME=FIT",
                     "*SURFACE BEHAVIOR, PRESSURE-OVERCLOSURE=LINEAR", "1.e6",
                     "*FRICTION", "0.2, 1.e5",
                     "*CONTACT PAIR, INTERACTION=FIT, TYPE=NODE TO SURFACE", "RING_IN, SHAFT_OUT",
                     "*BOUNDARY", "SHAFT_ALL, 1, 2",
                     "*STEP", "*STATIC, DIRECT", "1., 1.",
                     "*BOUNDARY", "RING_FACES, 2, 2, 0.",
                     "*NODE PRINT, NSET=RING_FACES, TOTALS=ONLY", "RF",
                     "*NODE PRINT, NSET=PROBE", "U",
                     "*NODE FILE", "U", "*EL FILE", "S",
                     "*END STEP",
                     "*STEP", "*STATIC, DIRECT", "0.1, 1.",
                     "*BOUNDARY", "RING_FACES, 2, 2, 0.1",
                     "*NODE PRINT, NSET=RING_FACES, TOTALS=ONLY", "RF",
                     "*NODE PRINT, NSET=PROBE", "U",
                     "*NODE FILE", "U", "*EL FILE", "S",
                     "*END STEP"]
    write("push_out.inp", deck)


def hertz():
    R, top, height = 50.0, 12.0, 10.0
    m = Mesh()
    theta_max = math.asin(top / R)
    th = with_mid(stations(0.06, 16, theta_max, 12))
    zs = with_mid(stations(1.0, 4, height, 8))
    ni, nj = (len(th) - 1) // 2, (len(zs) - 1) // 2
    arc = lambda t: (R * math.sin(t), R * (1.0 - math.cos(t)))
    p1 = arc(theta_max)
    corners = [(0.0, 0.0), p1, (top, height), (0.0, height)]

    def sphere(I, J):
        # Coons patch: bottom the arc, top the flat face, left the axis, right the cut
        u, v = I / (2 * ni), zs[J] / height
        b, t, l, r = arc(th[I]), (top * u, height), (0.0, zs[J]), (top, p1[1] + (height - p1[1]) * v)
        return tuple((1 - v) * b[c] + v * t[c] + (1 - u) * l[c] + u * r[c]
                     - ((1 - u) * (1 - v) * corners[0][c] + u * (1 - v) * corners[1][c]
                        + u * v * corners[2][c] + (1 - u) * v * corners[3][c]) for c in range(2))

    gs, rs = m.block(ni, nj, sphere)
    L = 20.0
    xs = with_mid(stations(2.5, 16, L, 8))
    ys = with_mid(stations(2.5, 16, L, 8))
    nb = (len(xs) - 1) // 2
    gb, rb = m.block(nb, nb, lambda I, J: (xs[I], -ys[2 * nb - J]))
    deck = ["*HEADING", "Hertz: sphere R 50 pushed 0.05 mm into a block, face-to-face penalty contact"]
    deck += m.node_lines()
    deck += m.element_lines([e for r in rs for e in r], "SPHERE")
    deck += m.element_lines([e for r in rb for e in r], "BLOCK")
    deck += listing("*NSET, NSET=AXIS", side(gs, ni, nj, "left") + side(gb, nb, nb, "left"))
    deck += listing("*NSET, NSET=SPHERE_TOP", side(gs, ni, nj, "top"))
    deck += listing("*NSET, NSET=BLOCK_BOTTOM", side(gb, nb, nb, "bottom"))
    # probes on the axis 5 mm above and below the contact (at the contact itself the two
    # codes' pointwise penetrations differ: CalculiX's face-to-face contact is weaker at the axis)
    j_sphere = min(range(len(zs)), key=lambda j: abs(zs[j] - 5.0) + (j % 2))
    j_block = min(range(len(ys)), key=lambda j: abs(ys[j] - 5.0) + (j % 2))
    deck += ["*NSET, NSET=PROBE", f"{gs[0, j_sphere]}, {gb[0, 2 * nb - j_block]}"]
    deck += surface("SPHERE_TIP", [(e, 1) for e in rs[0]])
    deck += surface("BLOCK_TOP", [(e, 3) for e in rb[-1]])
    deck += STEEL + ["*SOLID SECTION, ELSET=SPHERE, MATERIAL=STEEL",
                     "*SOLID SECTION, ELSET=BLOCK, MATERIAL=STEEL",
                     "*SURFACE INTERACTION, NAME=HARD",
                     "*SURFACE BEHAVIOR, PRESSURE-OVERCLOSURE=LINEAR", "1.e6",
                     "*CONTACT PAIR, INTERACTION=HARD, TYPE=SURFACE TO SURFACE", "SPHERE_TIP, BLOCK_TOP",
                     "*BOUNDARY", "AXIS, 1, 1", "BLOCK_BOTTOM, 1, 2",
                     "*STEP", "*STATIC, DIRECT", "0.2, 1.",
                     "*BOUNDARY", "SPHERE_TOP, 2, 2, -0.05",
                     "*NODE PRINT, NSET=SPHERE_TOP, TOTALS=ONLY", "RF",
                     "*NODE PRINT, NSET=PROBE", "U",
                     "*NODE FILE", "U", "*EL FILE", "S",
                     "*END STEP"]
    write("hertz.inp", deck)


def small_bellows():
    rc, bump, z0, length, stub, t = 50.0, 8.0, 5.0, 40.0, 5.0, 0.5
    total = z0 + length + stub

    def centre(z):
        if z0 < z < z0 + length:
            return rc + bump * math.sin(math.pi * (z - z0) / length) ** 2
        return rc

    # arc length along the centreline, by a fine polyline
    zs = [total * k / 20000 for k in range(20001)]
    pts = [(centre(z), z) for z in zs]
    s = [0.0]
    for p, q in zip(pts, pts[1:]):
        s.append(s[-1] + math.dist(p, q))

    def at(frac):
        """Point and unit outward normal at a fraction of the centreline's arc length."""
        target = frac * s[-1]
        lo, hi = 0, len(s) - 1
        while hi - lo > 1:
            mid = (lo + hi) // 2
            lo, hi = (mid, hi) if s[mid] <= target else (lo, mid)
        w = (target - s[lo]) / (s[hi] - s[lo])
        p = tuple(pts[lo][c] + w * (pts[hi][c] - pts[lo][c]) for c in range(2))
        dz = 1e-4
        z = p[1]
        dr = (centre(min(z + dz, total)) - centre(max(z - dz, 0.0))) / (min(z + dz, total) - max(z - dz, 0.0))
        norm = math.hypot(dr, 1.0)
        return p, (1.0 / norm, -dr / norm)

    n_along, n_thick = 80, 2
    m = Mesh()
    plies = []
    for k in range(2):
        def position(I, J, k=k):
            (r, z), (nr, nz) = at(J / (2 * n_along))
            d = (k + I / (2.0 * n_thick)) * t  # ply k spans offsets k t .. (k + 1) t
            return (r + d * nr, z + d * nz)
        plies.append(m.block(n_thick, n_along, position))
    deck = ["*HEADING", "Small bellows: one convolution, two 0.5 mm plies, J2 with a hardening table,",
            "200 degC and 1 MPa inside, then 4 mm axial compression (NLGEOM)"]
    deck += m.node_lines()
    for k, (g, rows) in enumerate(plies):
        deck += m.element_lines([e for r in rows for e in r], f"PLY{k + 1}")
    deck += listing("*ELSET, ELSET=PLY1_INNER", [r[0] for r in plies[0][1]])
    deck += ["*ELSET, ELSET=PLIES", "PLY1, PLY2", "*NSET, NSET=ALLN, GENERATE", f"1, {len(m.nodes)}"]
    deck += listing("*NSET, NSET=BOTTOM", side(plies[0][0], n_thick, n_along, "bottom") + side(plies[1][0], n_thick, n_along, "bottom"))
    deck += listing("*NSET, NSET=TOP", side(plies[0][0], n_thick, n_along, "top") + side(plies[1][0], n_thick, n_along, "top"))
    crown = plies[1][0][2 * n_thick, n_along]
    deck += ["*NSET, NSET=PROBE", f"{crown}"]
    deck += surface("PLY1_OUT", [(r[-1], 2) for r in plies[0][1]])
    deck += surface("PLY2_IN", [(r[0], 4) for r in plies[1][1]])
    deck += ["*MATERIAL, NAME=AISI304", "*ELASTIC", "200000., 0.3",
             "*EXPANSION, ZERO=20.", "1.875e-5",
             "*PLASTIC", "300., 0.", "330., 0.02", "380., 0.2",
             "*SOLID SECTION, ELSET=PLIES, MATERIAL=AISI304",
             "*SURFACE INTERACTION, NAME=PLIES",
             "*SURFACE BEHAVIOR, PRESSURE-OVERCLOSURE=LINEAR", "1.e5",
             "*CONTACT PAIR, INTERACTION=PLIES, TYPE=SURFACE TO SURFACE", "PLY1_OUT, PLY2_IN",
             "*INITIAL CONDITIONS, TYPE=TEMPERATURE", "ALLN, 20.",
             "*BOUNDARY", "BOTTOM, 2, 2",
             "*STEP, NLGEOM, INC=1000", "*STATIC, DIRECT", "0.25, 1.",
             "*BOUNDARY", "TOP, 2, 2, 0.",
             "*TEMPERATURE", "ALLN, 200.",
             "*DLOAD", "PLY1_INNER, P4, 1.",
             "*NODE PRINT, NSET=TOP, TOTALS=ONLY", "RF",
             "*NODE PRINT, NSET=PROBE", "U",
             "*NODE FILE", "U", "*EL FILE", "S, PEEQ",
             "*END STEP",
             "*STEP, NLGEOM, INC=1000", "*STATIC, DIRECT", "0.1, 1.",
             "*BOUNDARY", "TOP, 2, 2, -4.",
             "*NODE PRINT, NSET=TOP, TOTALS=ONLY", "RF",
             "*NODE PRINT, NSET=PROBE", "U",
             "*NODE FILE", "U", "*EL FILE", "S, PEEQ",
             "*END STEP"]
    write("small_bellows.inp", deck)


if __name__ == "__main__":
    lame()
    shrink_fit()
    adjusted_fit()
    push_out()
    hertz()
    small_bellows()
    spun_disc()
    kinematic_cylinder()
