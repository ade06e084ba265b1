#!/usr/bin/env bash
# Installs the Debian 12 packages Talus needs.
# Skips apt entirely when every package is already installed, so re-runs are fast.
# Usage: bash scripts/setup.sh      (as root, or with sudo available)
set -euo pipefail

packages=(
  libeigen3-dev coinor-libipopt-dev libnlopt-cxx-dev libnlopt-dev libsundials-dev
  libsuitesparse-dev libgtest-dev libbenchmark-dev libcli11-dev nlohmann-json3-dev
  libyaml-cpp-dev gnuplot-nox pkg-config cmake g++ make
  # CHOLMOD's supernodal factorisation spends most of its time in BLAS; the
  # reference BLAS that SuiteSparse pulls in is about 2x slower than OpenBLAS.
  libopenblas-dev
  # OMPL (Reeds–Shepp curves, kinematic/); its CMake config names the Boost libraries.
  libompl-dev libboost-serialization-dev libboost-filesystem-dev libboost-system-dev
  # GDAL: the CLI's terrain rasters (GeoTIFF, .hgt, ... in; GeoTIFF out); gdal-bin for gdalinfo.
  libgdal-dev gdal-bin
  # Python bindings (python/, `import talus`): pybind11, the interpreter's headers, numpy;
  # pytest runs their tests under CTest and matplotlib draws python/examples/plan.py.
  pybind11-dev python3-dev python3-numpy python3-pytest python3-matplotlib
  # `pip install .` into a venv (pyproject.toml, setup.py), and the Jupyter notebooks
  # (python/notebooks/): executed by nbclient in an ipykernel, rendered by nbconvert.
  python3-venv python3-pip python3-setuptools python3-wheel
  python3-nbclient python3-nbformat python3-ipykernel python3-nbconvert
  # mpirun for `talus sweep` across ranks and its tests (libopenmpi-dev comes with SUNDIALS).
  openmpi-bin libopenmpi-dev
)

if ! command -v dpkg-query >/dev/null 2>&1 || ! command -v apt-get >/dev/null 2>&1; then
  echo "setup.sh: dpkg-query/apt-get not found; this script supports Debian 12 only." >&2
  exit 1
fi

missing=()
for p in "${packages[@]}"; do
  status=$(dpkg-query -W -f='${db:Status-Abbrev}' "$p" 2>/dev/null || true)
  [[ "$status" == ii* ]] || missing+=("$p")
done

if [[ ${#missing[@]} -eq 0 ]]; then
  echo "setup.sh: all ${#packages[@]} required packages are installed."
  exit 0
fi

echo "setup.sh: installing ${#missing[@]} missing package(s): ${missing[*]}"
if [[ $(id -u) -eq 0 ]]; then
  sudo=()
elif command -v sudo >/dev/null 2>&1; then
  sudo=(sudo)
else
  echo "setup.sh: need root to install ${missing[*]} (run as root or install sudo)." >&2
  exit 1
fi

export DEBIAN_FRONTEND=noninteractive
apt=("${sudo[@]}" env DEBIAN_FRONTEND=noninteractive apt-get -o DPkg::Lock::Timeout=300)
if ! "${apt[@]}" update; then
  echo "setup.sh: 'apt-get update' failed." >&2
  exit 1
fi
if ! "${apt[@]}" install -y --no-install-recommends "${packages[@]}"; then
  echo "setup.sh: 'apt-get install' failed for: ${packages[*]}" >&2
  exit 1
fi

# Verify: fail loudly if anything is still missing.
still=()
for p in "${packages[@]}"; do
  status=$(dpkg-query -W -f='${db:Status-Abbrev}' "$p" 2>/dev/null || true)
  [[ "$status" == ii* ]] || still+=("$p")
done
if [[ ${#still[@]} -ne 0 ]]; then
  echo "setup.sh: still not installed after apt-get: ${still[*]}" >&2
  exit 1
fi
echo "setup.sh: done."
