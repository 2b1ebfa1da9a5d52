#!/usr/bin/env bash
# Install what oscidrum needs from Debian 12 (bookworm) packages. Idempotent: installs only what
# is missing. Needs root (or sudo). PyPI is not used: Python packages come from Debian too.
set -euo pipefail

packages=(
  build-essential cmake ninja-build pkg-config git
  libboost-dev                  # Boost.Math (TOMS 748 roots)
  libtomlplusplus-dev           # config files
  nlohmann-json3-dev            # JSON output
  libhdf5-dev                   # sweep --hdf5 (HDF5 C library)
  zlib1g-dev                    # sweep --hdf5: chunks deflated in the worker threads
  libcli11-dev                  # command-line parsing
  libeigen3-dev                 # independent linear solves in the tests
  libgtest-dev libgmock-dev     # unit tests
  libbenchmark-dev              # benchmarks (separate target)
  clang-format                  # formatting check in CI
  python3 python3-dev python3-pybind11 pybind11-dev
  python3-numpy python3-matplotlib python3-pytest
  python3-h5py                  # reads sweep --hdf5 files (tests/python/test_hdf5.py)
  python3-pip python3-setuptools python3-wheel
  emscripten                    # the browser explorer: the engine compiled to WebAssembly
  chromium                      # the explorer's end-to-end test (headless)
  python3-pandas python3-tqdm   # DataFrames of results, progress bars of studies
  python3-xarray python3-netcdf4  # studies as xarray Datasets and netCDF files
  python3-distributed           # Dask: studies on a cluster (and its test)
  python3-mpi4py openmpi-bin    # mpi4py.futures: studies under MPI (and its test)
  python3-nbclient python3-nbformat python3-ipykernel  # the notebooks, run by the tests
)
# node and npm for the explorer (web/): Debian's, unless a node is already installed
if ! command -v node >/dev/null; then packages+=(nodejs); fi
if ! command -v npm >/dev/null; then packages+=(npm); fi

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -eq 0 ]; then
  exit 0
fi
echo "setup: installing ${missing[*]}" >&2
SUDO=""
if [ "$(id -u)" != 0 ]; then SUDO="sudo"; fi
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -qq
$SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
