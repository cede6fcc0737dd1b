#!/bin/bash
# Installs what building, running and testing the program needs on Debian 12:
# deal.II 9.4.1 (with its SuiteSparse, Trilinos, p4est, PETSc, MPI), CMake,
# numdiff, GoogleTest, ccache and the Python plotting packages used by the
# doc and benchmark scripts. Does nothing if everything is there already.
set -euo pipefail

packages=(libdeal.ii-dev cmake g++ make numdiff libgtest-dev ccache
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
