#!/usr/bin/env bash
# Installs the Debian packages MedialMesh builds, runs and tests with.
# Runs apt-get only when something is missing, so repeated calls are fast.
set -euo pipefail

packages=(
  cmake ninja-build g++ ccache pkg-config
  libocct-foundation-dev libocct-modeling-data-dev
  libocct-modeling-algorithms-dev libocct-data-exchange-dev
  libocct-visualization-dev # BRep_Tool.hxx includes a header shipped only here
  libboost-dev nlohmann-json3-dev
  libgtest-dev libgmock-dev libbenchmark-dev
  pybind11-dev python3-dev
  freecad xvfb xauth
  librsvg2-bin # rsvg-convert: SVG pictures to PNG
  coinor-libcbc-dev # CBC: the integer program of interval assignment
  liblbfgs-dev # L-BFGS: smoothing's joint search round the worst elements
  gmsh python3-gmsh libgmsh-dev # the mesher we compare against, and a reader of our .msh
  calculix-ccx # the solver of the end-to-end FEM check
  python3-meshio python3-numpy # an independent reader of our mesh files
  python3-vtk9 # VTK's vtkMeshQuality (Verdict): the independent check of our quality measures
)

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done

if ((${#missing[@]})); then
  echo "deps: installing ${missing[*]}"
  sudo_cmd=()
  [ "$(id -u)" -eq 0 ] || sudo_cmd=(sudo)
  export DEBIAN_FRONTEND=noninteractive
  "${sudo_cmd[@]}" apt-get update
  "${sudo_cmd[@]}" apt-get install -y --no-install-recommends "${missing[@]}"
fi
