#!/bin/bash
# Installs the Debian 12 packages that building and testing the package need,
# if any is missing. Run as root (or with sudo available); non-interactive.
# usage: install_dependencies.sh [--tests]
set -euo pipefail
export DEBIAN_FRONTEND=noninteractive

packages=(cmake make g++ libcgal-dev libeigen3-dev libboost-dev libtet1.5-dev libtbb-dev libexodusii-dev libnetcdf-dev)
# --tests: also what the whole test suite needs (clang and its runtime for
# the fuzz targets of the readers; pybind11, Python headers, numpy and pytest
# for the Python bindings and their tests, pip, setuptools and venv for their
# `pip install .` test; meshio, netCDF4 and gmsh, readers
# of our .msh/.inp/.exo files written by others; doxygen, VTK and Xvfb for the
# manual and its rendered figures)
if [ "${1:-}" = "--tests" ]; then
  packages+=(clang libclang-rt-14-dev pybind11-dev python3-dev python3-numpy python3-pytest
             python3-pip python3-setuptools python3-venv python3-meshio python3-netcdf4 gmsh doxygen python3-vtk9 xvfb xauth)
fi

missing=()
for p in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done

if [ ${#missing[@]} -eq 0 ]; then
  echo "install_dependencies: all packages present (${packages[*]})"
  exit 0
fi

sudo=""
if [ "$(id -u)" -ne 0 ]; then
  sudo="sudo"
fi
echo "install_dependencies: installing ${missing[*]}"
$sudo apt-get update
$sudo env DEBIAN_FRONTEND=noninteractive apt-get install -y --no-install-recommends "${missing[@]}"
