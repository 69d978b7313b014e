#!/usr/bin/env bash
# ParaView (pvpython, Debian package paraview) opens a results file's XDMF sidecar with its
# default reader (OpenDataFile picks Xdmf3ReaderS) and with the legacy XDMF reader, and what it
# reads at the last increment equals `slideline post`: the displacement's extremes per
# component, the extremes of the element mean von Mises stress and of the nodal von Mises
# stress (never negative; its maximum printed beside the Gauss points' maximum, the closing
# table's); the t = 0 frame and every increment are time steps, and the reader's default time
# shows the mesh. Not in the test suite (ParaView is a 440 MB install); the suite checks the same file
# with meshio (tests/xdmf_readers.rs).
#
# usage: scripts/check-paraview.sh [RESULTS.xmf]   (default: the quick bellows, run here on 2 ranks)
# note: give pvpython the .xmf with a directory (./x.xmf or absolute): ParaView 5.11's Xdmf3
# reader joins a bare file name to the HDF5 name without a separator and aborts.
set -euo pipefail
here="$(cd "$(dirname "$0")/.." && pwd)"
command -v pvpython >/dev/null || { echo "installing ParaView (paraview)" >&2; DEBIAN_FRONTEND=noninteractive apt-get install -y -q paraview >/dev/null; }
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OPENBLAS_NUM_THREADS=1 OMPI_MCA_rmaps_base_oversubscribe=1
(cd "$here" && cargo build --release --quiet)
slideline="$here/target/release/slideline"
if [ $# -ge 1 ]; then
    xmf="$(cd "$(dirname "$1")" && pwd)/$(basename "$1")"
else
    work="$(mktemp -d)"; trap 'rm -rf "$work"' EXIT
    (cd "$work" && mpirun -n 2 "$slideline" bellows --quick --quiet -o quick.h5 > /dev/null)
    xmf="$work/quick.xmf"
fi
h5="${xmf%.xmf}.h5"
post=$("$slideline" post "$h5" --field displacement; "$slideline" post "$h5" --field von_mises_mean; "$slideline" post "$h5" --field nodal_von_mises; "$slideline" post "$h5" --field von_mises)
# the increments and the t = 0 frame
increments=$(/usr/bin/python3 -c "import h5py; print(len(h5py.File('$h5')['increments']) + 1)")
pvpython - "$xmf" "$increments" "$post" <<'PY' 2>&1 | grep -v '^ *[0-9]* *0x'
import sys
from paraview.simple import OpenDataFile, XDMFReader
from paraview import servermanager as sm
from paraview.vtk.numpy_interface import dataset_adapter as dsa
import numpy as np

path, increments, post = sys.argv[1], int(sys.argv[2]), sys.argv[3]
expected = {}
for line in post.splitlines():
    f = line.split()
    if len(f) > 2 and f[1] in ("min", "max"):
        expected[(f[0], f[1])] = float(f[2])

def last_step(reader, name):
    reader.UpdatePipelineInformation()
    times = list(reader.TimestepValues)
    reader.UpdatePipeline(times[-1])
    data = sm.Fetch(reader)
    while data.IsA("vtkMultiBlockDataSet"):
        data = data.GetBlock(0)
    w = dsa.WrapDataObject(data)
    u = np.asarray(w.PointData["displacement"])
    vm = np.asarray(w.CellData["von_mises_mean"])
    nodal = np.asarray(w.PointData["von_mises"])
    got = {("u_r", "min"): u[:, 0].min(), ("u_r", "max"): u[:, 0].max(), ("u_z", "min"): u[:, 1].min(), ("u_z", "max"): u[:, 1].max(),
           ("von_mises_mean", "min"): vm.min(), ("von_mises_mean", "max"): vm.max(),
           ("nodal_von_mises", "min"): nodal.min(), ("nodal_von_mises", "max"): nodal.max()}
    worst = max(abs(got[k] - v) / max(abs(v), 1e-12) for k, v in expected.items() if k in got)
    print(f"{name}: nodal von Mises {nodal.min():.3f} .. {nodal.max():.3f} MPa; at the Gauss points (the closing table's) "
          f"max {expected[('von_mises', 'max')]:.3f} MPa")
    reader.UpdatePipeline()
    first = sm.Fetch(reader)
    while first.IsA("vtkMultiBlockDataSet"):
        first = first.GetBlock(0)
    ok = len(times) == increments and worst < 1e-6 and nodal.min() >= 0.0 and first.GetNumberOfPoints() == data.GetNumberOfPoints()
    print(f"{name}: {len(times)} time steps (file: {increments}), points {data.GetNumberOfPoints()}, "
          f"point arrays {sorted(w.PointData.keys())}; extremes of u and element von Mises against slideline post: "
          f"largest relative difference {worst:.1e} -> {'ok' if ok else 'FAILED'}")
    return ok

default = OpenDataFile(path)
ok = last_step(default, f"default reader ({default.GetXMLName()})")
legacy = XDMFReader(FileNames=[path])
legacy.PointArrayStatus = legacy.GetProperty("PointArrayInfo")[::2]
ok = last_step(legacy, "legacy XDMF reader") and ok
sys.exit(0 if ok else 1)
PY
