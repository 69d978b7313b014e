# Sourced by the scripts that run CalculiX beside slideline (after `set -euo pipefail`): CalculiX
# (ccx, Debian package calculix-ccx) installed where it is missing, the MPI and thread
# environment of a root shell on a 2-core machine, slideline built, and the paths every one of
# them uses: $here (the repository), $slideline, $python (the one with h5py).
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
command -v ccx >/dev/null || { echo "installing CalculiX (calculix-ccx)" >&2; apt-get install -y calculix-ccx >/dev/null; }
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OPENBLAS_NUM_THREADS=1 OMP_NUM_THREADS=1 OMPI_MCA_rmaps_base_oversubscribe=1
(cd "$here" && cargo build --release --quiet)
slideline="$here/target/release/slideline"
python="${SLIDELINE_PYTHON:-/usr/bin/python3}"

# cd into a work directory: DIR (made, and kept) when given, else a temporary one removed on exit
work_in() {
    if [ -n "${1:-}" ]; then work="$1"; mkdir -p "$work"; else work="$(mktemp -d)"; trap 'rm -rf "$work"' EXIT; fi
    cd "$work"
}
