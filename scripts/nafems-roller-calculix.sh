#!/usr/bin/env bash
# NAFEMS's contact benchmark 1 (the 2-D cylinder roller) with friction mu = 0.1 run by CalculiX
# 2.20 on slideline's own mesh (tests/data/nafems_roller.geo, meshed again by Gmsh and written as
# CPE8 elements): surface-to-surface penalty contact with the penalty and stick slope slideline's
# pair has (penalty_factor 10: 10 E / h = 2.33e6 MPa/mm on the block's 0.3 mm edges), the 35 kN
# per mm in 20 equal increments as in tests/plane_sections.rs. Prints, for the cylinder's surface
# nodes below its centre, x, the contact pressure and the shear of ccx's last increment (CPRESS,
# CSHEAR1 of its .frd), the rows of tests/data/nafems_roller_ccx.csv.
#   scripts/nafems-roller-calculix.sh > tests/data/nafems_roller_ccx.csv
# Needs gmsh and calculix-ccx (installed with apt when missing); about a minute.
set -euo pipefail
here="$(cd "$(dirname "$0")/.." && pwd)"
command -v ccx >/dev/null || apt-get install -y calculix-ccx >/dev/null
command -v gmsh >/dev/null || apt-get install -y gmsh >/dev/null
python="${SLIDELINE_PYTHON:-/usr/bin/python3}"
work="$here/out/nafems-roller-calculix"
rm -rf "$work" && mkdir -p "$work" && cd "$work"
gmsh -2 -order 2 "$here/tests/data/nafems_roller.geo" -format inp -setnumber Mesh.SaveGroupsOfNodes 1 -o gmsh.inp >gmsh.log 2>&1
"$python" - <<'PY'
import re
# Gmsh's Abaqus file: nodes, T3D3 lines (end, middle, end) per physical curve, CPS8 quads,
# element and node sets by physical name
nodes, blocks, elsets, nsets, mode = [], {}, {}, {}, None
for line in open("gmsh.inp").read().splitlines():
    if line.startswith("*"):
        head = line.upper()
        if head.startswith("*NODE"):
            mode = ("node",)
        elif head.startswith("*ELEMENT"):
            kind, name = re.search(r"type=(\w+)", line, re.I).group(1), re.search(r"ELSET=(\w+)", line, re.I).group(1)
            mode = ("element", name)
            blocks[name] = (kind, [])
        elif head.startswith("*ELSET"):
            mode = ("elset", re.search(r"ELSET=(\w+)", line, re.I).group(1))
            elsets[mode[1]] = []
        elif head.startswith("*NSET"):
            mode = ("nset", re.search(r"NSET=(\w+)", line, re.I).group(1))
            nsets[mode[1]] = []
        else:
            mode = None
        continue
    values = [v for v in line.replace(" ", "").split(",") if v]
    if not values or mode is None:
        continue
    if mode[0] == "node":
        nodes.append(values)
    elif mode[0] == "element":
        blocks[mode[1]][1].append([int(v) for v in values])
    else:
        (elsets if mode[0] == "elset" else nsets)[mode[1]] += [int(v) for v in values]
lines = {e[0]: e[1:] for kind, els in blocks.values() if kind == "T3D3" for e in els}
quads = {e[0]: e[1:] for kind, els in blocks.values() if kind == "CPS8" for e in els}

def faces(curve):
    """The quad faces (element, S1..S4) along a physical curve's line elements."""
    out = []
    for line in elsets[curve]:
        ends = {lines[line][0], lines[line][2]}
        for q, conn in quads.items():
            face = next((f for f in range(4) if {conn[f], conn[(f + 1) % 4]} == ends), None)
            if face is not None:
                out.append(f"{q}, S{face + 1}")
                break
    return out

deck = ["*NODE"] + [",".join(n) for n in nodes]
for surface, name in (("cylinder", "CYL"), ("block", "BLOCK")):
    deck.append(f"*ELEMENT, TYPE=CPE8, ELSET={name}")
    deck += [", ".join(map(str, [e] + quads[e])) for e in elsets[surface]]
for name in ("cylinder_top", "cylinder_axis", "block_axis", "block_bottom", "cylinder_surface"):
    ids = sorted(set(nsets[name]))
    deck.append(f"*NSET, NSET={name.upper()}")
    deck += [", ".join(map(str, ids[i:i + 10])) + "," for i in range(0, len(ids), 10)]
deck += ["*SURFACE, NAME=MASTER"] + faces("block_top") + ["*SURFACE, NAME=SLAVE"] + faces("cylinder_surface")
deck += """*MATERIAL, NAME=ROLLER
*ELASTIC
210000., 0.3
*MATERIAL, NAME=ALUMINIUM
*ELASTIC
70000., 0.3
*SOLID SECTION, ELSET=CYL, MATERIAL=ROLLER
1.
*SOLID SECTION, ELSET=BLOCK, MATERIAL=ALUMINIUM
1.
*CONTACT PAIR, INTERACTION=SI, TYPE=SURFACE TO SURFACE
SLAVE, MASTER
*SURFACE INTERACTION, NAME=SI
*SURFACE BEHAVIOR, PRESSURE-OVERCLOSURE=LINEAR
2.333e6
*FRICTION
0.1, 2.333e6
*BOUNDARY
CYLINDER_AXIS, 1, 1
BLOCK_AXIS, 1, 1
BLOCK_BOTTOM, 1, 2
*STEP, INC=1000
*STATIC
0.05, 1., 1e-5, 0.05
*CLOAD
CYLINDER_TOP, 2, -17500.
*CONTACT FILE
CSTR, CDIS
*END STEP""".splitlines()
open("roller.inp", "w").write("\n".join(deck) + "\n")
PY
OMP_NUM_THREADS=2 ccx roller >ccx.log 2>&1 || { tail -5 ccx.log >&2; exit 1; }
"$python" - <<'PY'
import re
lines = open("roller.frd").read().splitlines()
last = max(i for i, l in enumerate(lines) if l.startswith(" -4  CONTACT"))
values = {}
for l in lines[last + 1:]:
    if l.startswith(" -3"):
        break
    if l.startswith(" -1"):
        values[int(l[3:13])] = [float(l[13 + 12 * k:25 + 12 * k]) for k in range(6)]
deck = open("roller.inp").read()
coords = {int(p[0]): (float(p[1]), float(p[2])) for p in (l.split(",") for l in deck.split("*NODE\n")[1].split("\n*")[0].splitlines())}
surface = [int(v) for v in re.findall(r"\d+", deck.split("*NSET, NSET=CYLINDER_SURFACE\n")[1].split("\n*")[0])]
print("# NAFEMS roller, mu 0.1, CalculiX 2.20 (scripts/nafems-roller-calculix.sh): x (mm), CPRESS, CSHEAR1 (MPa)")
for x, y, n in sorted((*coords[n], n) for n in surface):
    if y < 10.0:
        v = values.get(n, [0.0] * 6)
        print(f"{x:.6f},{v[3]:.4f},{v[4]:.4f}")
PY
