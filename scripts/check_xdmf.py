#!/usr/bin/env python3
"""Reads a slideline results file's XDMF sidecar with meshio, as a user would, and checks it
against the HDF5 file read with h5py: every increment is a step at the history's time, the
points and cells are the mesh (Q8, or 6-node triangles), the first step is the undeformed state at t = 0
(with every array of the last step, zeros), the
displacement is (u_r, u_z, 0) of the increment, the element fields are the stored ones, and the
nodal stresses are the Gauss-point stresses carried to the nodes, computed here independently:
the biquadratic fit through the 3 x 3 points in elements where no point has yielded, the
nearest Gauss point's value in the others (ANSYS's ERESX default; a triangle's 9 points are
fitted by the complete quadratic in least squares, a reduced Q8's 2 x 2 by the bilinear
field, a reduced T6's 3 by the linear one, their spare slots NaN and never read), averaged over the elements at
a node; von Mises from the averaged components (never negative), the equivalent plastic strain
copied (within the Gauss values' range). Prints one line per check; exits 1 on the first
failure.

usage: check_xdmf.py RESULTS.xmf   (needs Debian's python3-meshio, python3-h5py, python3-numpy)
"""
import os
import sys

import h5py
import meshio
import numpy as np


def stated(dataset):
    """The absolute resolution a field is stored to ([output] precision = "resolution"), or 0."""
    text = dataset.attrs.get("resolution")
    if text is None:
        return 0.0
    text = text.decode() if isinstance(text, bytes) else str(text)
    return 0.0 if text.startswith("full") else float(text.split()[0])


def fail(message):
    print(f"FAILED: {message}")
    sys.exit(1)


def nodal_from_gauss(conn, gauss, nodes, copied, reduced):
    """Mean over elements of each element's nodal values: the biquadratic fit through the 3 x 3
    Gauss values at the nodes, or (elements where `copied`) the nearest Gauss point's value;
    the elements where `reduced` use their first slots: a Q8's 4 (2 x 2), a T6's 3."""
    g = np.sqrt(0.6)
    pts = np.array([-g, 0.0, g])
    natural = [(-1, -1), (1, -1), (1, 1), (-1, 1), (0, -1), (1, 0), (0, 1), (-1, 0)]

    def lag(k, x):
        return np.prod([(x - pts[m]) / (pts[k] - pts[m]) for m in range(3) if m != k])

    # Gauss point q = 3 * j + i at (xi_i, eta_j)
    fit = np.array([[lag(q % 3, xi) * lag(q // 3, eta) for q in range(9)] for xi, eta in natural])
    nearest = np.zeros((8, 9))
    for a, (xi, eta) in enumerate(natural):
        nearest[a, 3 * (int(np.sign(eta)) + 1) + int(np.sign(xi)) + 1] = 1.0
    tri_fit, tri_nearest = triangle_recovery()
    reduced_fit, reduced_nearest = reduced_recovery()
    tri3_fit, tri3_nearest = triangle3_recovery()
    sums = np.zeros(nodes)
    counts = np.zeros(nodes)
    for e in range(conn.shape[0]):
        triangle = conn[e, 6] == conn[e, 0]
        if reduced[e] and triangle:
            values = (tri3_nearest if copied[e] else tri3_fit) @ gauss[e][:3]
            nodes_of = conn[e, :6]
        elif reduced[e]:
            values = (reduced_nearest if copied[e] else reduced_fit) @ gauss[e][:4]
            nodes_of = conn[e]
        elif triangle:
            values = (tri_nearest if copied[e] else tri_fit) @ gauss[e]
            nodes_of = conn[e, :6]
        else:
            values = (nearest if copied[e] else fit) @ gauss[e]
            nodes_of = conn[e]
        np.add.at(sums, nodes_of, values)
        np.add.at(counts, nodes_of, 1.0)
    return sums / counts


def nearest_points(natural, pts):
    """Row a: 1 at the point nearest node `natural[a]`, or the mean of those equally near."""
    nearest = np.zeros((len(natural), len(pts)))
    for a, (x, y) in enumerate(natural):
        d = np.hypot(pts[:, 0] - x, pts[:, 1] - y)
        ties = d <= d.min() * (1.0 + 1e-12)
        nearest[a, ties] = 1.0 / ties.sum()
    return nearest


def reduced_recovery():
    """The 8 x 4 matrices of a reduced Q8, its 2 x 2 Gauss points at +-1/sqrt(3) (q = 2 j + i):
    the bilinear field through them at the nodes, and each node's nearest point (a mid-side
    node has two, averaged)."""
    g = 1.0 / np.sqrt(3.0)
    pts = np.array([(-g, -g), (g, -g), (-g, g), (g, g)])
    natural = [(-1, -1), (1, -1), (1, 1), (-1, 1), (0, -1), (1, 0), (0, 1), (-1, 0)]
    lag = lambda k, x: 0.5 * (1.0 + (x if k == 1 else -x) / g)
    fit = np.array([[lag(q % 2, xi) * lag(q // 2, eta) for q in range(4)] for xi, eta in natural])
    return fit, nearest_points(natural, pts)


def triangle3_recovery():
    """The 6 x 3 matrices of a T6 on CalculiX's 3 points (1/6, 1/6), (2/3, 1/6), (1/6, 2/3):
    the linear field through them at the nodes, and each node's nearest point (ties averaged)."""
    pts = np.array([(1 / 6, 1 / 6), (2 / 3, 1 / 6), (1 / 6, 2 / 3)])
    natural = [(0, 0), (1, 0), (0, 1), (0.5, 0), (0.5, 0.5), (0, 0.5)]
    basis = np.array([[1.0, x, y] for x, y in pts])
    fit = np.array([[1.0, x, y] for x, y in natural]) @ np.linalg.inv(basis)
    return fit, nearest_points(natural, pts)


def triangle_recovery():
    """The 6 x 9 matrices of a 6-node triangle: the least-squares quadratic through its 9
    Gauss points at the nodes, and each node's nearest point. The points are Stroud's conical
    product rule, built here from its definition: Gauss-Legendre in s, Gauss-Jacobi for the
    weight (1 - t) in t, xi = s (1 - t), eta = t, s running first."""
    legendre = (np.polynomial.legendre.leggauss(3)[0] + 1.0) / 2.0
    # monic orthogonal polynomial of degree 3 for the weight (1 - t) on [0, 1], from moments
    m = [1.0 / ((k + 1) * (k + 2)) for k in range(6)]
    c = np.linalg.solve([[m[i + j] for j in range(3)] for i in range(3)], [-m[i + 3] for i in range(3)])
    jacobi = np.sort(np.roots([1.0, c[2], c[1], c[0]]).real)
    pts = np.array([(s * (1.0 - t), t) for t in jacobi for s in legendre])
    mono = lambda x, y: [1.0, x, y, x * x, x * y, y * y]
    a = np.array([mono(*p) for p in pts])
    natural = [(0, 0), (1, 0), (0, 1), (0.5, 0), (0.5, 0.5), (0, 0.5)]
    fit = np.array([mono(*n) for n in natural]) @ np.linalg.pinv(a)
    nearest = np.zeros((6, 9))
    for k, n in enumerate(natural):
        nearest[k, np.argmin(np.hypot(pts[:, 0] - n[0], pts[:, 1] - n[1]))] = 1.0
    return fit, nearest


def main():
    xmf = sys.argv[1]
    h5 = h5py.File(os.path.splitext(xmf)[0] + ".h5", "r")
    reader = meshio.xdmf.TimeSeriesReader(xmf)
    points, cells = reader.read_points_cells()
    coords = h5["mesh/coordinates"][:]
    conn = h5["mesh/connectivity"][:]
    triangles = conn[:, 6] == conn[:, 0]
    if triangles.all():
        cell_type, cell_nodes = "triangle6", conn[:, :6]
    elif not triangles.any():
        cell_type, cell_nodes = "quad8", conn
    else:
        fail("a mixed mesh: meshio 5 does not read XDMF's mixed cells with quadratic quadrilaterals")
    if not np.array_equal(points[:, :2], coords) or cells[0].type != cell_type or not np.array_equal(cells[0].data, cell_nodes):
        fail("points or cells differ from /mesh")
    print(f"mesh: {points.shape[0]} points, {cells[0].data.shape[0]} {cell_type} cells")
    increments = sorted(h5["increments"].keys())
    rows = len(h5["history/time"])
    if reader.num_steps != len(increments) + 1:
        fail(f"{reader.num_steps} steps for {len(increments)} increments and the t = 0 frame")
    t, point_data, initial_cells = reader.read_data(0)
    if t != 0.0 or np.any(point_data["displacement"] != 0.0):
        fail("the first step is not the undeformed state at t = 0")
    # ParaView keeps one array list over time: the t = 0 frame has every array the last one has
    _, last_points, last_cells = reader.read_data(len(increments))
    if sorted(point_data) != sorted(last_points) or sorted(initial_cells) != sorted(last_cells):
        fail(f"the t = 0 frame's arrays {sorted(point_data)} {sorted(initial_cells)} differ from the last frame's {sorted(last_points)} {sorted(last_cells)}")
    if any(np.any(v[0] != 0.0) for k, v in initial_cells.items() if k != "rank") or any(np.any(v != 0.0) for k, v in point_data.items() if k != "temperature"):
        fail("the t = 0 frame's fields are not zeros")
    for k, name in enumerate(increments):
        t, point_data, cell_data = reader.read_data(k + 1)
        inc = h5["increments"][name]
        if abs(t - inc.attrs["time"]) > 1e-12 or abs(t - h5["history/time"][int(name) - 1]) > 1e-12:
            fail(f"step {k}: time {t} against the increment's {inc.attrs['time']}")
        u = point_data["displacement"]
        if not (np.array_equal(u, inc["nodal/displacement"][:]) and np.all(u[:, 2] == 0.0)):
            fail(f"step {k}: displacement differs from {name}/nodal/displacement")
        for field in ("von_mises_mean", "equivalent_plastic_strain_max"):
            if (field in inc) != (field in cell_data):
                fail(f"step {k}: {field} is in one of the two files only")
            if field in inc and not np.array_equal(cell_data[field][0], inc[field][:]):
                fail(f"step {k}: {field} differs")
    stress = inc["stress"][:].astype(float) if "stress" in inc else np.zeros((0, 9, 4))
    # a reduced element (4 or 3 Gauss points) holds NaN in its spare slots, and only there
    used = h5["mesh/gauss_points"][:] if "gauss_points" in h5["mesh"] else np.full(conn.shape[0], 9)
    reduced = used < 9
    spare = np.arange(9)[None, :] >= used[:, None]
    if "stress" in inc and not np.array_equal(np.isnan(stress).any(axis=2), spare):
        fail("last step: the stress is NaN elsewhere than in the reduced elements' spare slots")
    # 32-bit fields ([output] precision = "single") round each value to 6e-8 of itself
    rounding = 1e-12 if inc["nodal/von_mises"].dtype == np.float64 else 3e-7
    ep = inc["equivalent_plastic_strain"][:] if "equivalent_plastic_strain" in inc else np.zeros((conn.shape[0], 9))
    copied = np.any(ep > 0.0, axis=1)
    nodal = {}
    for c, field in enumerate(("stress_rr", "stress_zz", "stress_tt", "stress_rz") if "stress" in inc else ()):
        nodal[field] = expected = nodal_from_gauss(conn, stress[:, :, c], points.shape[0], copied, reduced)
        scale = np.nanmax(np.abs(stress[:, :, c])) or 1.0
        worst = np.abs(point_data[field] - expected).max() / scale
        # fields kept to a stated resolution: the Gauss values' errors, carried to a corner
        # (weights summing to at most about 3 in size), and the nodal value's own
        allowed = max(rounding, 10.0 * max(stated(inc["stress"]), stated(inc["nodal/" + field])) / scale)
        if worst > allowed:
            fail(f"last step: nodal {field} differs from the Gauss points carried to the nodes by {worst:.2e}")
    if nodal:
        a, b, c, t = (nodal[f] for f in ("stress_rr", "stress_zz", "stress_tt", "stress_rz"))
        mises = np.sqrt(0.5 * ((a - b) ** 2 + (b - c) ** 2 + (c - a) ** 2) + 3.0 * t * t)
        vm = point_data["von_mises"]
        allowed = max(1e-9, rounding) * mises.max() + 10.0 * stated(inc["nodal/von_mises"])
        if np.abs(vm - mises).max() > allowed or vm.min() < 0.0:
            fail("last step: nodal von_mises is not the von Mises stress of the nodal components")
        gauss_max = np.nanmax(inc["von_mises"][:])
        print(f"nodal von Mises {vm.min():.3f} .. {vm.max():.3f} MPa, Gauss points' maximum {gauss_max:.3f} MPa")
    if "equivalent_plastic_strain" in inc:
        ep_nodal = point_data["equivalent_plastic_strain"]
        expected = nodal_from_gauss(conn, ep, points.shape[0], np.ones(conn.shape[0], dtype=bool), reduced)
        allowed = rounding + 10.0 * max(stated(inc["equivalent_plastic_strain"]), stated(inc["nodal/equivalent_plastic_strain"]))
        if np.abs(ep_nodal - expected).max() > allowed or ep_nodal.min() < 0.0 or ep_nodal.max() > np.nanmax(ep) + allowed:
            fail("last step: nodal equivalent_plastic_strain is not the nearest Gauss values averaged")
    if "contact" in inc:
        expected = np.zeros(points.shape[0])
        for pair in inc["contact"]:
            for name in inc["contact"][pair]:
                nodes = h5["mesh/contact"][pair][name]["nodes"][:]
                np.maximum.at(expected, nodes, inc["contact"][pair][name]["pressure"][:])
        resolution = stated(inc["nodal/contact_pressure"]) + max(
            (stated(inc["contact"][pair][name]["pressure"]) for pair in inc["contact"] for name in inc["contact"][pair]), default=0.0)
        if np.abs(point_data["contact_pressure"] - expected).max() > resolution:
            fail("last step: nodal contact_pressure differs from the largest pass pressure at each slave node")
        print(f"contact pressure at the nodes equals the passes' (max {expected.max():.3f} MPa, {int(point_data['contact_status'].sum())} nodes in contact)")
    print(f"{len(increments)} increment steps after the t = 0 frame (of {rows} history rows) at the history's times; displacement and element fields equal the HDF5 file's;")
    if "stress" in inc:
        print(f"nodal stresses at the last step equal the Gauss-point stresses carried to the nodes (max |s_rr| {np.abs(point_data['stress_rr']).max():.3f} MPa)")
    print(f"fields: {sorted(point_data)} at the nodes, {sorted(cell_data)} per element")
    print("ok")


if __name__ == "__main__":
    main()
