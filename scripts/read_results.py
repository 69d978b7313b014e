#!/usr/bin/env python3
"""Reads a slideline results file with plain h5py: the layout is documented in docs/results.md.

    python3 scripts/read_results.py out/lame.h5
"""
import sys

import h5py
import numpy as np

path = sys.argv[1] if len(sys.argv) > 1 else "out/lame.h5"
with h5py.File(path, "r") as f:
    print("deck units:", f.attrs["units"])
    print("ranks:", f.attrs["ranks"], " PETSc options:", f.attrs["petsc_options"])
    history = f["history"]
    columns = sorted(history)
    print("history columns:", ", ".join(columns))
    for row in range(len(history["step"])):
        print("  step %d  increment %d  load factor %.4f  Newton %d" % (
            history["step"][row], history["increment"][row], history["load_factor"][row], history["newton_iterations"][row]))
    last = sorted(f["increments"])[-1]
    u = f["increments"][last]["nodal/displacement"][:, :2]  # (u_r, u_z, 0) for ParaView
    vm = f["increments"][last]["von_mises"][:]
    x = f["mesh/coordinates"][:]
    k = np.argmax(np.hypot(u[:, 0], u[:, 1]))
    print("increment %s: max |u| = %.4g mm at (r, z) = (%.2f, %.2f); max von Mises %.4g MPa" % (
        last, np.hypot(*u[k]), x[k, 0], x[k, 1], vm.max()))
