# Sourced by tools/run and tools/test: installs what is missing (Debian 12, as root), then
# configures and builds into build/ (Release with debug info).
set -euo pipefail
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
BUILD="${RAD_BUILD_DIR:-$ROOT/build}"

rad_packages=(g++ cmake ninja-build pkg-config libembree-dev libtbb-dev libglm-dev libgtest-dev
  libgmock-dev libbenchmark-dev libcli11-dev libfmt-dev nlohmann-json3-dev libstb-dev
  libtinyexr-dev libtinygltf-dev)

rad_install_missing() {
  local missing=()
  for p in "$@"; do
    dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q 'install ok installed' || missing+=("$p")
  done
  ((${#missing[@]} == 0)) && return 0
  echo "Installing: ${missing[*]}"
  local sudo=""
  [ "$(id -u)" -ne 0 ] && sudo="sudo"
  $sudo apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
}

rad_build() {
  rad_install_missing "${rad_packages[@]}"
  if [ ! -f "$BUILD/build.ninja" ]; then
    cmake -S "$ROOT" -B "$BUILD" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo
  fi
  cmake --build "$BUILD" -j "$(nproc)"
}
