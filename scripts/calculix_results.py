#!/usr/bin/env python3
"""Reads CalculiX's output (jobname.dat, .frd, .sta) and slideline's history CSV, and prints
them side by side. Used by scripts/compare-calculix.sh; plain Python, no packages.

usage: calculix_results.py JOB_DIR/JOB SET CCX_SECONDS RUN1.csv RUN1_SECONDS RUN1_POST.txt RUN2.csv RUN2_SECONDS RUN2_POST.txt
"""
import csv
import math
import sys


def dat_forces(path, set_name):
    """[(time, fy)] of the 'total force' blocks of set_name (per 2-degree segment)."""
    out, header = [], None
    for line in open(path):
        t = line.strip()
        if not t:
            continue
        if " for set " in t:
            name, time = t.split(" for set ")[1].split(" and time")
            header = (t.startswith("total force") and name.strip() == set_name, float(time))
            continue
        if header and header[0]:
            out.append((header[1], float(t.split()[1])))
    return out


def frd_blocks(path):
    """{time: {name: {node: [values]}}} of an ASCII .frd file's result blocks."""
    out, current, time = {}, None, None
    for line in open(path):
        if line.startswith("  100CL"):
            time = float(line[12:24])
        elif line.startswith(" -4"):
            current = out.setdefault(time, {}).setdefault(line.split()[1], {})
        elif line.startswith(" -1") and current is not None:
            # fixed width: ' -1', the node (10 characters), the values (12 each)
            body = line[13:].rstrip("\n")
            current[int(line[3:13])] = [float(body[k:k + 12]) for k in range(0, len(body) - 11, 12)]
        elif line.startswith(" -3"):
            current = None
    return out


def frd_last(path):
    """(max von Mises, max |u_r|, max |u_z|) of the last DISP and STRESS blocks of an ASCII
    .frd file (x is r, y is z)."""
    blocks = {}
    for time in sorted(frd_blocks(path).items(), key=lambda t: t[0]):
        blocks.update({name: list(values.values()) for name, values in time[1].items()})
    ur = max(abs(v[0]) for v in blocks["DISP"])
    uz = max(abs(v[1]) for v in blocks["DISP"])
    mises = 0.0
    for s in blocks["STRESS"]:
        sxx, syy, szz, sxy, syz, szx = s[:6]
        mises = max(mises, math.sqrt(0.5 * ((sxx - syy) ** 2 + (syy - szz) ** 2 + (szz - sxx) ** 2) + 3 * (sxy ** 2 + syz ** 2 + szx ** 2)))
    return mises, ur, uz


def sta(path):
    """(increments, Newton iterations) from the .sta summary."""
    rows = [l.split() for l in open(path) if l.strip() and l.split()[0].isdigit()]
    return len(rows), sum(int(r[3]) for r in rows)


def history(path, set_name):
    # the CSV's header cells carry their units ("time [s]"): key the columns by name alone
    rows = [{k.split(" [")[0]: v for k, v in r.items()} for r in csv.DictReader(open(path))]
    col = f"reaction_{set_name}_z_2deg"
    if rows and col not in rows[0]:
        sys.exit(f"slideline's history has no column {col}: is {set_name} a set with a prescribed displacement?")
    return rows, [(float(r["time"]), float(r[col])) for r in rows]


def post_max(path):
    """(max von Mises, max |u_r|, max |u_z|) from `slideline post --field` listings."""
    mises = float("nan")
    comps = {}
    for line in open(path):
        f = line.split()
        if len(f) > 2 and f[1] in ("min", "max"):
            if f[0] == "von_mises" and f[1] == "max":
                mises = float(f[2])
            if f[0] in ("u_r", "u_z"):
                comps.setdefault(f[0], []).append(abs(float(f[2])))
    return mises, max(comps.get("u_r", [0])), max(comps.get("u_z", [0]))


def main():
    job, set_name, ccx_seconds = sys.argv[1], sys.argv[2], float(sys.argv[3])
    runs = [(sys.argv[4 + 3 * k], float(sys.argv[5 + 3 * k]), sys.argv[6 + 3 * k]) for k in range(2)]
    theirs = dat_forces(job + ".dat", set_name)
    ccx = frd_last(job + ".frd")
    ccx_inc, ccx_its = sta(job + ".sta")
    ours = [history(r[0], set_name) for r in runs]
    print(f"reaction at {set_name}, N per 2-degree segment (CalculiX's convention)")
    print(f"{'time':>8} {'CalculiX':>13} {'slideline 1':>13} {'slideline 2':>13} {'diff %':>8}")
    scale = max(abs(f) for _, f in theirs) or 1.0
    worst = 0.0
    for k, (t, f) in enumerate(theirs):
        vals = [h[1][k][1] if k < len(h[1]) else float("nan") for h in ours]
        diff = 100.0 * (vals[0] - f) / scale
        worst = max(worst, abs(diff))
        print(f"{t:8.4f} {f:13.6e} {vals[0]:13.6e} {vals[1]:13.6e} {diff:8.3f}")
    print(f"largest difference: {worst:.3f} % of the largest CalculiX reaction")
    print()
    r1, r2 = post_max(runs[0][2]), post_max(runs[1][2])
    its = [sum(int(float(r["newton_iterations"])) for r in h[0]) for h in ours]
    incs = [len(h[0]) for h in ours]
    print(f"{'at the end':<28} {'CalculiX 2.20':>14} {'slideline 1 rank':>17} {'slideline 2 ranks':>18}")
    print(f"{'max von Mises, MPa':<28} {ccx[0]:14.4g} {r1[0]:17.4g} {r2[0]:18.4g}   (CalculiX: extrapolated to nodes; slideline: Gauss points)")
    print(f"{'max |u_r|, mm':<28} {ccx[1]:14.5g} {r1[1]:17.5g} {r2[1]:18.5g}")
    print(f"{'max |u_z|, mm':<28} {ccx[2]:14.5g} {r1[2]:17.5g} {r2[2]:18.5g}")
    print(f"{'increments':<28} {ccx_inc:14d} {incs[0]:17d} {incs[1]:18d}")
    print(f"{'Newton iterations':<28} {ccx_its:14d} {its[0]:17d} {its[1]:18d}")
    print(f"{'wall time, s':<28} {ccx_seconds:14.2f} {runs[0][1]:17.2f} {runs[1][1]:18.2f}")
    print(f"{'time ratio CalculiX / slideline':<31} {'':>11} {ccx_seconds / runs[0][1]:17.2f} {ccx_seconds / runs[1][1]:18.2f}")


if __name__ == "__main__":
    main()
