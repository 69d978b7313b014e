#!/usr/bin/env bash
# slideline: set-up and entry point.
#   ./run.sh [FLAGS]         install what is missing, build (release), run the main job on 2 ranks:
#                            the seed paper's bellows joint (FLAGS as for `slideline bellows`, e.g. --quick)
#   ./run.sh test            install what is missing, build, run every test (MPI ones included)
#   ./run.sh bench           run the criterion benchmarks
set -euo pipefail
cd "$(dirname "$0")"

# OpenMPI refuses to start as root without these; one BLAS thread per MPI rank.
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OPENBLAS_NUM_THREADS=1
# Containers often report fewer slots than cores: allow 2 ranks anyway.
export OMPI_MCA_rmaps_base_oversubscribe=1

PACKAGES=(petsc-dev libslepc-real3.18-dev libopenmpi-dev openmpi-bin libhdf5-openmpi-dev hdf5-tools libclang-dev pkg-config libopenblas0-pthread)
# the tests read results as users do, with meshio and h5py: Debian's own, for Debian's python3
# (which refuses pip installs), called by its path whatever python3 comes first on PATH; and
# Chromium, which renders the design report headless as a person would see it
TEST_PACKAGES=(python3-meshio python3-h5py python3-numpy chromium)
export SLIDELINE_PYTHON=/usr/bin/python3

install_missing() {
    local missing=()
    for p in "${PACKAGES[@]}" "$@"; do
        dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
    done
    if [ ${#missing[@]} -gt 0 ]; then
        echo "run.sh: installing ${missing[*]}"
        local sudo=""
        [ "$(id -u)" -eq 0 ] || sudo="sudo"
        $sudo apt-get update -q
        DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -q "${missing[@]}"
    fi
    if ! command -v cargo >/dev/null; then
        echo "run.sh: cargo not found; install Rust from https://rustup.rs" >&2
        exit 1
    fi
}

if [ "${1:-}" = test ]; then install_missing "${TEST_PACKAGES[@]}"; else install_missing; fi
# ./run.sh --quick (or any other bellows flag) is the main job with that flag
if [ "${1:-main}" != "main" ] && [ "${1#-}" != "${1:-}" ]; then set -- main "$@"; fi
case "${1:-main}" in
    main)
        # the seed paper's bellows joint on 2 ranks: results, table and pictures in out/
        cargo build --release
        mkdir -p out
        exec mpirun -n 2 target/release/slideline bellows --output out/bellows.h5 "${@:2}"
        ;;
    test)
        cargo build --release --all-targets
        exec cargo test --release "${@:2}"
        ;;
    bench)
        exec cargo bench "${@:2}"
        ;;
    *)
        echo "usage: ./run.sh [bellows flags] | test | bench" >&2
        exit 2
        ;;
esac
