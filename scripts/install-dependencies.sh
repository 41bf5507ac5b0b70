#!/usr/bin/env bash
# Installs the Debian 12 packages IGAView builds and tests with, skipping those already present.
# ParaView 5.11's VTK 9.2 comes from python3-paraview/paraview-dev; libvtk9-dev must NOT be
# installed (it owns the same vtkmodules as python3-paraview).
set -euo pipefail

packages=(
  build-essential cmake ninja-build git pkg-config
  python3-paraview paraview paraview-dev
  qtbase5-dev libqt5svg5-dev qttools5-dev qtxmlpatterns5-dev-tools
  libopenmpi-dev mpi-default-dev libglew-dev libdouble-conversion-dev liblz4-dev libtiff-dev
  libutfcpp-dev libopenexr-dev libglm-dev libgtest-dev googletest
  xvfb xauth libgl1-mesa-dri
  clang libclang-rt-14-dev
)

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -eq 0 ]; then
  echo "install-dependencies: all ${#packages[@]} packages present"
  exit 0
fi

if dpkg-query -W -f='${Status}' libvtk9-dev 2>/dev/null | grep -q "install ok installed"; then
  echo "install-dependencies: libvtk9-dev is installed and conflicts with python3-paraview; remove it first" >&2
  exit 1
fi

sudo=""
if [ "$(id -u)" -ne 0 ]; then
  sudo="sudo"
fi
echo "install-dependencies: installing ${missing[*]}"
$sudo apt-get update -qq
DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq "${missing[@]}" >/dev/null
