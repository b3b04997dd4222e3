# Sourced by tools/run and tools/test: installs what is missing (Debian 12, as root), then
# configures and builds into build/ (Release with debug info).
set -euo pipefail
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
# RAD_SANITIZE (address,undefined or thread) builds an instrumented tree in its own folder.
RAD_SANITIZE="${RAD_SANITIZE:-}"
if [ -n "$RAD_SANITIZE" ]; then
  BUILD="${RAD_BUILD_DIR:-$ROOT/build-${RAD_SANITIZE//,/-}}"
else
  BUILD="${RAD_BUILD_DIR:-$ROOT/build}"
fi

rad_packages=(g++ cmake ninja-build pkg-config libembree-dev libtbb-dev libglm-dev libgtest-dev
  libgmock-dev libbenchmark-dev libcli11-dev libfmt-dev nlohmann-json3-dev libstb-dev
  libtinyexr-dev libtinygltf-dev libcpp-httplib-dev libtinyobjloader-dev)

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
  # Configured every time (a second when nothing changed), so a changed option takes effect.
  cmake -S "$ROOT" -B "$BUILD" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo \
    -DRAD_SANITIZE="$RAD_SANITIZE" ${RAD_SANITIZE:+-DRAD_BUILD_BENCH=OFF} >/dev/null
  cmake --build "$BUILD" -j "$(nproc)"
}

# Node tools the tests use (the Khronos glTF validator), installed under build/npm. Not fatal:
# the tests that need them skip with a message when they are missing.
rad_install_node_tools() {
  command -v npm >/dev/null 2>&1 || rad_install_missing nodejs npm || true
  if command -v npm >/dev/null 2>&1 && [ ! -d "$BUILD/npm/node_modules/gltf-validator" ]; then
    npm install --prefix "$BUILD/npm" --no-audit --no-fund --loglevel=error \
      gltf-validator@2.0.0-dev.3.10 >/dev/null || echo "warning: could not install gltf-validator"
  fi
}

# rad serve's front end and its browser test: three.js, lil-gui and playwright-core from npm
# (exact versions in tools/e2e/package.json) under build/web, where rad looks for them (web/
# node_modules beside the rad executable), and Debian's Chromium for the end-to-end test. Not
# fatal: rad serve says what is missing, and the browser test skips.
rad_install_web() {
  rad_install_missing libcpp-httplib-dev || echo "warning: could not install libcpp-httplib-dev"
  command -v npm >/dev/null 2>&1 || rad_install_missing nodejs npm || true
  [ -x /usr/bin/chromium ] || rad_install_missing chromium || echo "warning: could not install chromium"
  command -v npm >/dev/null 2>&1 || { echo "warning: npm missing: rad serve has no page"; return 0; }
  local web="$BUILD/web"
  if ! cmp -s "$ROOT/tools/e2e/package.json" "$web/package.json" ||
      [ ! -f "$web/node_modules/three/build/three.module.js" ] ||
      [ ! -f "$web/node_modules/lil-gui/dist/lil-gui.esm.min.js" ] ||
      [ ! -d "$web/node_modules/playwright-core" ]; then
    mkdir -p "$web"
    cp "$ROOT/tools/e2e/package.json" "$web/package.json"
    npm install --prefix "$web" --no-audit --no-fund --loglevel=error >/dev/null ||
      echo "warning: could not install three, lil-gui and playwright-core"
  fi
}
