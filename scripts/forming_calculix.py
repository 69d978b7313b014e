#!/usr/bin/env python3
"""The forming as CalculiX and slideline each ran the same deck, side by side at every time
both reached, ply by ply: its displacement (largest, and the largest difference between the
two at one node), each convolution's crest (the ply's outside radius at its highest point) and
the ply's thickness there, and the largest equivalent plastic strain at its nodes. Used by
scripts/compare-forming-calculix.sh; needs h5py (python3-h5py).

usage: forming_calculix.py JOB.frd JOB.inp SLIDELINE.h5
"""
import math
import sys

import h5py

from calculix_results import frd_blocks


def inp_sets(path, names):
    """{name: [node]} of the deck's *NSET cards named."""
    sets, name = {}, None
    for line in open(path):
        if line.startswith("*"):
            card = line.upper()
            name = None
            if card.startswith("*NSET") and "NSET=" in card:
                key = card.split("NSET=")[1].split(",")[0].strip()
                if key in names:
                    name = key
                    sets[name] = []
        elif name:
            sets[name] += [int(v) for v in line.replace(",", " ").split()]
    return sets


def crests(coordinates, displacement, outer, inner):
    """Each convolution's crest: (z, outside radius, ply thickness there) at the outside nodes
    radially highest between their neighbours along the meridian (the straight tube's axial
    order), over 1 mm above the lowest."""
    at = lambda n: (coordinates[n][0] + displacement[n][0], coordinates[n][1] + displacement[n][1])
    line = [at(n) for n in sorted(outer, key=lambda n: coordinates[n][1])]
    low = min(r for r, _ in line)
    inside = [at(n) for n in inner]
    out = []
    for k in range(1, len(line) - 1):
        r, z = line[k]
        if r > low + 1.0 and r >= line[k - 1][0] and r > line[k + 1][0]:
            out.append((z, r, min(math.hypot(r - ri, z - zi) for ri, zi in inside)))
    return out


def main(frd, inp, h5):
    ccx = frd_blocks(frd)
    f = h5py.File(h5, "r")
    plies = sorted(k for k in f["mesh/node_sets"].keys() if k.startswith("PLY") and k[3:].isdigit())
    sets = inp_sets(inp, set(plies) | {f"{k}_{side}" for k in plies for side in ("OUTER", "INNER")} | {"TANGENT_B"})
    ids = list(f["mesh/node_ids"][:])
    index = {n: k for k, n in enumerate(ids)}
    coordinates = {n: f["mesh/coordinates"][k] for n, k in index.items()}
    increments = {round(float(g.attrs["time"]), 9): g for g in f["increments"].values() if g.attrs.get("complete", 1)}
    every = [n for k in plies for n in sets[k]]
    print(f"{'time':>7} {'ply':>5} {'|u| max, mm':>19} {'max |du| / max |u|':>19} {'crests: r, mm (CalculiX/slideline)':>36} "
          f"{'thickness there, mm':>28} {'PEEQ max, %':>16}")
    last = None
    for time in sorted(t for t in ccx if "DISP" in ccx[t]):
        group = increments.get(round(time, 9))
        if group is None:
            continue
        u_sl = {n: group["nodal/displacement"][index[n]] for n in every}
        u_cx = {n: ccx[time]["DISP"][n][:2] for n in every}
        for k in plies:
            ply = sets[k]
            umax = [max(math.hypot(*u[n]) for n in ply) for u in (u_cx, u_sl)]
            du = max(math.hypot(u_cx[n][0] - u_sl[n][0], u_cx[n][1] - u_sl[n][1]) for n in ply)
            c = [crests(coordinates, u, sets[k + "_OUTER"], sets[k + "_INNER"]) for u in (u_cx, u_sl)]
            pe_cx = max(ccx[time]["PE"][n][0] for n in ply) if "PE" in ccx[time] else float("nan")
            pe_sl = max(group["nodal/equivalent_plastic_strain"][index[n]] for n in ply)
            radii = " ".join(f"{a[1]:.3f}/{b[1]:.3f}" for a, b in zip(*c))
            thick = " ".join(f"{a[2]:.4f}/{b[2]:.4f}" for a, b in zip(*c))
            print(f"{time:7.4f} {k.lower():>5} {umax[0]:8.4f} / {umax[1]:8.4f} {du / umax[1]:19.2e} {radii:>36} {thick:>28} "
                  f"{100 * pe_cx:7.3f} / {100 * pe_sl:6.3f}")
        last = (time, group)
    if last and "TANGENT_B" in sets:
        time, group = last
        far = sets["TANGENT_B"]
        uz = [sum(u[n][1] for n in far) / len(far) for u in ({n: ccx[time]["DISP"][n] for n in far}, {n: group["nodal/displacement"][index[n]] for n in far})]
        print(f"the far tangent's axial displacement at {time:.4f}: CalculiX {uz[0]:.3f} mm, slideline {uz[1]:.3f} mm")


if __name__ == "__main__":
    if len(sys.argv) != 4:
        sys.exit(__doc__)
    main(*sys.argv[1:])
