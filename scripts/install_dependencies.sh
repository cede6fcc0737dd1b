#!/bin/bash
# Installs what building, running and testing the program needs on Debian 12:
# deal.II 9.4.1 (with its SuiteSparse, Trilinos, p4est, PETSc, MPI), CMake,
# an optimised BLAS with threads (OpenBLAS built with pthreads: CHOLMOD's
# supernodal factorisation runs its dense kernels on the rank's threads,
# about 1.8x faster on two cores than the serial OpenBLAS in one pair of
# runs by hand, which itself was 1.4x faster than the reference BLAS;
# everything else keeps the BLAS on one thread, see
# include/back_ends/blas_threads.h), numdiff, GoogleTest, ccache and the
# Python plotting packages of the doc and benchmark scripts. Debian's
# alternatives give the threaded OpenBLAS precedence over other BLAS builds.
# Does nothing if all is there.
set -euo pipefail

packages=(libdeal.ii-dev libsuitesparse-dev openmpi-bin libopenblas0-pthread cmake g++ make
          numdiff libgtest-dev ccache strace
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
