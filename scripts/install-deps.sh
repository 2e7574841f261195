#!/usr/bin/env bash
# Installs the Debian 12 packages constrict needs, if any is missing (apt-get; sudo when not root).
# python3-setuptools/wheel/venv/pip: `pip install --no-build-isolation .` offline; shapely, meshio,
# dask, distributed: the Python conversions and the cluster test (docs/python.md).
set -euo pipefail
PKGS=(build-essential cmake ccache libcgal-dev libgmp-dev libmpfr-dev libboost-dev libeigen3-dev
      libgtest-dev libgmock-dev libbenchmark-dev libcli11-dev nlohmann-json3-dev libtbb-dev
      libfast-float-dev libnanoflann-dev libpng-dev pybind11-dev python3-dev python3-numpy
      python3-setuptools python3-wheel python3-venv python3-pip
      python3-shapely python3-meshio python3-dask python3-distributed
      clang-14 libclang-rt-14-dev)  # (clang: the libFuzzer smoke of .ci/run, docs/fuzzing.md)
missing=()
for p in "${PKGS[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
[ ${#missing[@]} -eq 0 ] && exit 0
echo "installing Debian packages: ${missing[*]}"
SUDO=""
[ "$(id -u)" -ne 0 ] && SUDO="sudo"
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -qq
$SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
