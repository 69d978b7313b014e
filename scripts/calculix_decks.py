#!/usr/bin/env python3
"""Compares the final nodal displacements of a CalculiX run (JOB.dat, its last
'displacements' blocks, any set) with slideline's results file, node by node, and prints one
line: nodes compared, the largest |u_r| and |u_z| of CalculiX, the largest difference of
each as a fraction of that, and the difference of u_r at the node where ccx's |u_r| is largest (the
headline number). A deck that prints no displacement but element stresses (*EL PRINT, S), or
the displacement of one node only (pret2: its prescribed reference node), is compared by
element too: each element's mean stress over its integration points, and the
headline is the difference of each element's largest mean component (CalculiX's x, y, z, xy
are slideline's r, z, t, rz). A heat deck's nodal temperatures are compared instead. Used by scripts/calculix-test-decks.sh; needs h5py and numpy
(Debian's python3-h5py).

usage: calculix_decks.py JOB.dat RESULTS.h5
"""
import sys

import h5py
import numpy as np


def dat_displacements(path):
    """{node: (u_r, u_z)} of the last time's 'displacements' blocks."""
    blocks, current, time = {}, None, None
    for line in open(path):
        t = line.strip()
        if t.startswith("displacements") and " and time" in t:
            time = float(t.split(" and time")[1])
            current = blocks.setdefault(time, {})
            continue
        if not t or not t[0].isdigit() and not t[0] == "-":
            if t and not t[0].isdigit():
                current = None if not t.startswith("displacements") else current
            continue
        p = t.split()
        if current is not None and len(p) >= 3 and p[0].isdigit():
            current[int(p[0])] = (float(p[1]), float(p[2]))
    if not blocks:
        return {}
    return blocks[max(blocks)]


def dat_element_stresses(path):
    """{element: mean (sxx, syy, szz, sxy)} of the last time's 'stresses' blocks."""
    blocks, current = {}, None
    for line in open(path):
        t = line.strip()
        if t and not t[0].isdigit():
            current = None
            if t.startswith("stresses") and " and time" in t:
                current = blocks.setdefault(float(t.split(" and time")[1]), {})
            continue
        p = t.split()
        if current is not None and len(p) >= 6:
            current.setdefault(int(p[0]), []).append([float(v) for v in p[2:6]])
    if not blocks:
        return {}
    return {e: np.mean(v, axis=0) for e, v in blocks[max(blocks)].items()}


def compare_stresses(dat, results):
    ccx = dat_element_stresses(dat)
    if not ccx:
        return
    with h5py.File(results, "r") as f:
        last = sorted(k for k in f["increments"] if f["increments"][k].attrs.get("complete", 1))[-1]
        stress = f["increments"][last]["stress"][:]
        ids = f["mesh/element_ids"][:]
    # (a reduced element's last 5 Gauss slots are NaN)
    ours = {int(e): np.nanmean(stress[k], axis=0) for k, e in enumerate(ids)}
    common = [e for e in ccx if e in ours]
    if not common:
        print("no element of ccx's stresses in the results file")
        return
    parts = []
    worst = 0.0
    for e in common:
        k = int(np.argmax(np.abs(ccx[e])))
        d = abs(ours[e][k] - ccx[e][k]) / abs(ccx[e][k])
        worst = max(worst, d)
        parts.append(f"element {e} s{('xx', 'yy', 'zz', 'xy')[k]} {ccx[e][k]:.4e} MPa {100 * d:.2f} %")
    print(f"element-mean stresses of {len(common)} elements, largest component of each: " + "; ".join(parts) + f"; largest difference {100 * worst:.2f} %")


def dat_temperatures(path):
    """{node: temperature} of the last time's 'temperatures' blocks."""
    blocks, current = {}, None
    for line in open(path):
        t = line.strip()
        if t and not t[0].isdigit():
            current = None
            if t.startswith("temperatures") and " and time" in t:
                current = blocks.setdefault(float(t.split(" and time")[1]), {})
            continue
        p = t.split()
        if current is not None and len(p) == 2:
            current[int(p[0])] = float(p[1])
    return blocks[max(blocks)] if blocks else {}


def compare_temperatures(dat, results):
    """A heat deck: every node's temperature against ccx's, as a fraction of ccx's range."""
    ccx = dat_temperatures(dat)
    with h5py.File(results, "r") as f:
        step = sorted(f["heat"])[-1]
        t = f["heat"][step]["temperature"][:]
        ids = f["mesh/node_ids"][:]
    ours = {int(n): t[k] for k, n in enumerate(ids)}
    common = [n for n in ccx if n in ours]
    if not common:
        print("no temperature printed by ccx")
        return
    a = np.array([ccx[n] for n in common])
    b = np.array([ours[n] for n in common])
    spread = a.max() - a.min()
    k = int(np.argmax(np.abs(a - b)))
    print(
        f"{len(common)} nodes: ccx's temperatures {a.min():.4g} to {a.max():.4g}; largest difference {abs(a[k] - b[k]):.4g}"
        f" ({100 * abs(a[k] - b[k]) / spread:.3f} % of the range) at node {common[k]}; median {100 * np.median(np.abs(a - b)) / spread:.3f} %"
    )


def main():
    with h5py.File(sys.argv[2], "r") as f:
        heat_only = "heat" in f and not len(f["increments"])
    if heat_only:
        compare_temperatures(sys.argv[1], sys.argv[2])
        return
    ccx = dat_displacements(sys.argv[1])
    if not ccx and not dat_element_stresses(sys.argv[1]):
        print("no displacement or element stress printed by ccx")
    compare_displacements(ccx, sys.argv[2])
    if len(ccx) < 2:
        compare_stresses(sys.argv[1], sys.argv[2])


def compare_displacements(ccx, results):
    if not ccx:
        return
    with h5py.File(results, "r") as f:
        last = sorted(k for k in f["increments"] if f["increments"][k].attrs.get("complete", 1))[-1]
        u = f["increments"][last]["nodal/displacement"][:, :2]
        ids = f["mesh/node_ids"][:]
    ours = {int(n): u[k] for k, n in enumerate(ids)}
    common = [n for n in ccx if n in ours]
    if not common:
        print("no displacement printed by ccx")
        return
    a = np.array([ccx[n] for n in common])
    b = np.array([ours[n] for n in common])
    scale = np.abs(a).max(axis=0)
    diff = np.abs(a - b).max(axis=0)
    rel = [d / s if s > 0 else 0.0 for d, s in zip(diff, scale)]
    # the headline: u_r at the node of ccx's largest |u_r| (the rim of a disc, a fit's bore)
    peak = int(np.argmax(np.abs(a[:, 0])))
    at_peak = abs(a[peak, 0] - b[peak, 0]) / abs(a[peak, 0])
    print(
        f"{len(common)} nodes: max |u_r| {scale[0]:.4e}, |u_z| {scale[1]:.4e} mm; largest difference {100 * rel[0]:.3f} % / {100 * rel[1]:.3f} %;"
        f" u_r at node {common[peak]} (ccx's largest) {100 * at_peak:.3f} %"
    )


main()
