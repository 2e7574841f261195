#!/usr/bin/env bash
# Installs the Debian 12 packages constrict needs, if any is missing (apt-get; sudo when not root).
set -euo pipefail
PKGS=(build-essential cmake ccache libcgal-dev libgmp-dev libmpfr-dev libboost-dev libeigen3-dev
      libgtest-dev libgmock-dev libbenchmark-dev libcli11-dev nlohmann-json3-dev libtbb-dev
      libfast-float-dev libnanoflann-dev libpng-dev pybind11-dev python3-dev python3-numpy
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
