#!/usr/bin/env bash
# Installs the Debian packages voxgi builds and tests with. Idempotent and non-interactive.
set -euo pipefail

packages=(
  build-essential cmake pkg-config ccache git
  libopenvdb-dev libopenvdb-tools libnanovdb-dev libboost-iostreams-dev libblosc-dev
  libembree-dev libtbb-dev libopenexr-dev libimath-dev
  libglm-dev libglfw3-dev libepoxy-dev libegl-dev libgl-dev libegl-mesa0 libgl1-mesa-dri mesa-utils
  libassimp-dev nlohmann-json3-dev libstb-dev libimgui-dev
  libgtest-dev xvfb xauth
  gnuplot-nox
  python3-skimage  # test_metrics_reference compares PSNR, SSIM and Pearson with scikit-image
  python3-openvdb  # test_vdb_python reads every dump with pyopenvdb.readAll
  clang libclang-rt-14-dev  # scripts/fuzz.sh: libFuzzer with AddressSanitizer and UBSan
)

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done

if [ ${#missing[@]} -eq 0 ]; then
  echo "setup: all ${#packages[@]} packages present"
  exit 0
fi

SUDO=""
if [ "$(id -u)" -ne 0 ]; then SUDO="sudo"; fi
export DEBIAN_FRONTEND=noninteractive
echo "setup: installing ${missing[*]}"
$SUDO apt-get update -q
$SUDO apt-get install -y -q --no-install-recommends "${missing[@]}"
