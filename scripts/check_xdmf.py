#!/usr/bin/env python3
"""Reads a slideline results file's XDMF sidecar with meshio, as a user would, and checks it
against the HDF5 file read with h5py: every increment is a step at the history's time, the
points and Q8 cells are the mesh, the displacement is (u_r, u_z, 0) of the increment, the
element fields are the stored ones, and the nodal stresses are the Gauss-point stresses carried
to the nodes (biquadratic fit through the 3 x 3 points, averaged over the elements at a node),
computed here independently. Prints one line per check; exits 1 on the first failure.

usage: check_xdmf.py RESULTS.xmf   (needs: pip install meshio h5py numpy)
"""
import os
import sys

import h5py
import meshio
import numpy as np


def fail(message):
    print(f"FAILED: {message}")
    sys.exit(1)


def nodal_from_gauss(conn, gauss, nodes):
    """Mean over elements of the biquadratic fit through the 3 x 3 Gauss values, at the nodes."""
    g = np.sqrt(0.6)
    pts = np.array([-g, 0.0, g])
    natural = [(-1, -1), (1, -1), (1, 1), (-1, 1), (0, -1), (1, 0), (0, 1), (-1, 0)]

    def lag(k, x):
        return np.prod([(x - pts[m]) / (pts[k] - pts[m]) for m in range(3) if m != k])

    # Gauss point q = 3 * j + i at (xi_i, eta_j)
    w = np.array([[lag(q % 3, xi) * lag(q // 3, eta) for q in range(9)] for xi, eta in natural])
    sums = np.zeros(nodes)
    counts = np.zeros(nodes)
    for e in range(conn.shape[0]):
        values = w @ gauss[e]
        np.add.at(sums, conn[e], values)
        np.add.at(counts, conn[e], 1.0)
    return sums / counts


def main():
    xmf = sys.argv[1]
    h5 = h5py.File(os.path.splitext(xmf)[0] + ".h5", "r")
    reader = meshio.xdmf.TimeSeriesReader(xmf)
    points, cells = reader.read_points_cells()
    coords = h5["mesh/coordinates"][:]
    conn = h5["mesh/connectivity"][:]
    if not np.array_equal(points[:, :2], coords) or cells[0].type != "quad8" or not np.array_equal(cells[0].data, conn):
        fail("points or cells differ from /mesh")
    print(f"mesh: {points.shape[0]} points, {cells[0].data.shape[0]} quad8 cells")
    increments = sorted(h5["increments"].keys())
    rows = len(h5["history/time"])
    if reader.num_steps != len(increments):
        fail(f"{reader.num_steps} steps for {len(increments)} increments")
    for k, name in enumerate(increments):
        t, point_data, cell_data = reader.read_data(k)
        inc = h5["increments"][name]
        if abs(t - inc.attrs["time"]) > 1e-12 or abs(t - h5["history/time"][int(name) - 1]) > 1e-12:
            fail(f"step {k}: time {t} against the increment's {inc.attrs['time']}")
        u = point_data["displacement"]
        if not (np.array_equal(u[:, :2], inc["displacement"][:]) and np.all(u[:, 2] == 0.0)):
            fail(f"step {k}: displacement differs from {name}/displacement")
        for field in ("von_mises_mean", "equivalent_plastic_strain_max"):
            if (field in inc) != (field in cell_data):
                fail(f"step {k}: {field} is in one of the two files only")
            if field in inc and not np.array_equal(cell_data[field][0], inc[field][:]):
                fail(f"step {k}: {field} differs")
    stress = inc["stress"][:] if "stress" in inc else np.zeros((0, 9, 4))
    for c, field in enumerate(("stress_rr", "stress_zz", "stress_tt", "stress_rz") if "stress" in inc else ()):
        expected = nodal_from_gauss(conn, stress[:, :, c], points.shape[0])
        scale = np.abs(stress[:, :, c]).max() or 1.0
        worst = np.abs(point_data[field] - expected).max() / scale
        if worst > 1e-12:
            fail(f"last step: nodal {field} differs from the Gauss points carried to the nodes by {worst:.2e}")
    if "contact" in inc:
        expected = np.zeros(points.shape[0])
        for pair in inc["contact"]:
            for name in inc["contact"][pair]:
                nodes = h5["mesh/contact"][pair][name]["nodes"][:]
                np.maximum.at(expected, nodes, inc["contact"][pair][name]["pressure"][:])
        if not np.array_equal(point_data["contact_pressure"], expected):
            fail("last step: nodal contact_pressure differs from the largest pass pressure at each slave node")
        print(f"contact pressure at the nodes equals the passes' (max {expected.max():.3f} MPa, {int(point_data['contact_status'].sum())} nodes in contact)")
    print(f"{reader.num_steps} steps (of {rows} history rows) at the history's times; displacement and element fields equal the HDF5 file's;")
    if "stress" in inc:
        print(f"nodal stresses at the last step equal the Gauss-point stresses carried to the nodes (max |s_rr| {np.abs(point_data['stress_rr']).max():.3f} MPa)")
    print(f"fields: {sorted(point_data)} at the nodes, {sorted(cell_data)} per element")
    print("ok")


if __name__ == "__main__":
    main()
