#!/usr/bin/env bash
# Installs the Debian 12 packages kdray needs to build, test and render. Idempotent and
# non-interactive; run as root (or with sudo available).
set -euo pipefail
packages=(
  cmake g++ make pkg-config git ca-certificates
  libassimp-dev libtinyobjloader-dev assimp-testmodels
  libcereal-dev libxxhash-dev nlohmann-json3-dev libfmt-dev libcli11-dev libtbb-dev
  ocl-icd-opencl-dev opencl-headers opencl-clhpp-headers pocl-opencl-icd clinfo
  libopenimageio-dev openimageio-tools libopenexr-dev libimath-dev
  libgtest-dev googletest
  python3-matplotlib python3-numpy bc
  clang libclang-rt-14-dev clang-15 libclc-15
  xz-utils
  munge slurm-wlm
)
missing=()
for package in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$package" 2>/dev/null | grep -q "install ok installed" || missing+=("$package")
done
if [ ${#missing[@]} -eq 0 ]; then
  echo "install-deps: all ${#packages[@]} packages present"
  exit 0
fi
SUDO=""
[ "$(id -u)" -eq 0 ] || SUDO="sudo"
echo "install-deps: installing ${missing[*]}"
$SUDO env DEBIAN_FRONTEND=noninteractive apt-get update -q
$SUDO env DEBIAN_FRONTEND=noninteractive apt-get install -y -q --no-install-recommends "${missing[@]}"
