# Sourced by tools/run, tools/test and the other tools: installs what is missing (Debian 12, as
# root), then configures and builds into build/ (Release with debug info). Safe to source from
# any shell: it sets no shell options (each script sets its own) and its functions return
# non-zero on failure.
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
# RAD_SANITIZE (address,undefined or thread) builds an instrumented tree in its own folder.
RAD_SANITIZE="${RAD_SANITIZE:-}"
if [ -n "$RAD_SANITIZE" ]; then
  BUILD="${RAD_BUILD_DIR:-$ROOT/build-${RAD_SANITIZE//,/-}}"
else
  BUILD="${RAD_BUILD_DIR:-$ROOT/build}"
fi

# What building rad needs (rad_run_packages), and what its tests and benchmarks add.
rad_run_packages=(g++ cmake ninja-build pkg-config libembree-dev libtbb-dev libglm-dev libcli11-dev
  libfmt-dev nlohmann-json3-dev libstb-dev libtinyexr-dev libtinygltf-dev libcpp-httplib-dev
  libtinyobjloader-dev libopenmpi-dev openmpi-bin)
rad_packages=("${rad_run_packages[@]}" libgtest-dev libgmock-dev libbenchmark-dev)

rad_install_missing() {
  local missing=()
  for p in "$@"; do
    dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q 'install ok installed' || missing+=("$p")
  done
  ((${#missing[@]} == 0)) && return 0
  echo "Installing: ${missing[*]}"
  local sudo=""
  [ "$(id -u)" -ne 0 ] && sudo="sudo"
  $sudo apt-get update -qq || return
  DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
}

# ThreadSanitizer sees the synchronisation only of code it instruments. Debian's libtbb and
# libembree3 are not instrumented, and both synchronise tasks in inline code (TBB's headers,
# compiled into Embree's BVH builder too): every hand-off of a task between threads looks like a
# race. So a thread-sanitized tree links its own oneTBB and Embree, built with -fsanitize=thread
# from Debian's source packages of the very versions installed (apt-get source through a private
# list, so the system's sources are left alone), under $BUILD/deps; built once, a few minutes.
# Embree gets its SSE2 kernels and triangles only: what rad uses. Prints the install prefix.
rad_fetch_source() {  # PACKAGE VERSION WORKDIR: unpacks the upstream tarball into WORKDIR
  local work="$3" key=/usr/share/keyrings/debian-archive-keyring.gpg
  mkdir -p "$work/lists/partial"
  echo "deb-src [signed-by=$key] http://deb.debian.org/debian bookworm main" >"$work/sources.list"
  local apt=(-o Dir::Etc::SourceList="$work/sources.list" -o Dir::Etc::SourceParts=/dev/null
    -o Dir::State::Lists="$work/lists" -o APT::Sandbox::User=root)
  apt-get "${apt[@]}" update -qq >"$work/apt.log" 2>&1 || { cat "$work/apt.log" >&2; return 1; }
  # Only the upstream tarball is used; Debian's patch set may be gone from the mirror.
  (cd "$work" && apt-get "${apt[@]}" source --download-only -qq "$1=$2" >>apt.log 2>&1) || true
  ls "$work"/"$1"_*.orig.tar.* >/dev/null 2>&1 ||
    { cat "$work/apt.log" >&2; echo "cannot fetch the source of $1 $2" >&2; return 1; }
  tar -xf "$work"/"$1"_*.orig.tar.* -C "$work"
}

rad_tsan_deps() {
  local prefix="$BUILD/deps" work="$BUILD/deps-src" log="$BUILD/deps-build.log"
  local flags=(-G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_INSTALL_PREFIX="$prefix"
    -DCMAKE_PREFIX_PATH="$prefix")
  if [ ! -f "$prefix/lib/cmake/TBB/TBBConfig.cmake" ]; then
    rad_install_missing xz-utils >&2
    local version
    version="$(dpkg-query -W -f='${source:Version}' libtbb-dev)"
    echo "Building oneTBB $version with -fsanitize=thread into $prefix (log: $log)" >&2
    rm -rf "$work" && rad_fetch_source onetbb "$version" "$work"
    { cmake -S "$work"/oneTBB-* -B "$work/build" "${flags[@]}" -DTBB_SANITIZE=thread \
        -DTBB_TEST=OFF -DTBB_EXAMPLES=OFF -DTBB_STRICT=OFF -DTBBMALLOC_BUILD=OFF \
        -DTBB_ENABLE_IPO=OFF && cmake --build "$work/build" -j "$(nproc)" &&
        cmake --install "$work/build"; } >"$log" 2>&1 || { tail -20 "$log" >&2; return 1; }
    rm -rf "$work"
  fi
  if [ ! -f "$prefix/lib/libembree3.so" ]; then
    local version tsan=(-DCMAKE_CXX_FLAGS=-fsanitize=thread -DCMAKE_C_FLAGS=-fsanitize=thread
      -DCMAKE_SHARED_LINKER_FLAGS=-fsanitize=thread -DCMAKE_EXE_LINKER_FLAGS=-fsanitize=thread
      "-DCMAKE_CXX_FLAGS_RELWITHDEBINFO=-O1 -g1" "-DCMAKE_C_FLAGS_RELWITHDEBINFO=-O1 -g1")
    version="$(dpkg-query -W -f='${source:Version}' libembree-dev)"
    echo "Building Embree $version with -fsanitize=thread into $prefix (log: $log)" >&2
    rm -rf "$work" && rad_fetch_source embree "$version" "$work"
    local src
    src="$(echo "$work"/embree-*)"
    touch "$src/readme.pdf"  # a documentation file the install wants (not in Debian's tarball)
    { cmake -S "$src" -B "$work/build" "${flags[@]}" "${tsan[@]}" \
        -DEMBREE_TASKING_SYSTEM=INTERNAL -DEMBREE_ISPC_SUPPORT=OFF -DEMBREE_TUTORIALS=OFF \
        -DEMBREE_MAX_ISA=SSE2 -DEMBREE_GEOMETRY_QUAD=OFF -DEMBREE_GEOMETRY_CURVE=OFF \
        -DEMBREE_GEOMETRY_SUBDIVISION=OFF -DEMBREE_GEOMETRY_USER=OFF \
        -DEMBREE_GEOMETRY_INSTANCE=OFF -DEMBREE_GEOMETRY_GRID=OFF -DEMBREE_GEOMETRY_POINT=OFF &&
        cmake --build "$work/build" -j "$(nproc)" && cmake --install "$work/build"; } >"$log" 2>&1 ||
      { tail -20 "$log" >&2; return 1; }
    rm -rf "$work"
  fi
  echo "$prefix"
}

rad_build() {  # [TARGET...]: those only (default: everything, tests and benchmarks included)
  rad_install_missing "${rad_packages[@]}" || return
  rad_configure -DRAD_BUILD_TESTS=ON -DRAD_BUILD_BENCH="$([ -n "$RAD_SANITIZE" ] && echo OFF || echo ON)" ||
    return
  cmake --build "$BUILD" -j "$(nproc)" ${1:+--target "$@"}
}

# What running rad needs: TARGET... built with the packages that building rad needs, none of the
# tests' (tools/test installs those and builds the tests). A build folder made here has the tests
# and benchmarks off; one that tools/test (or any rad_build) made keeps them on, so switching
# between tools/run and tools/test rebuilds nothing rad is made of.
rad_build_to_run() {  # TARGET...
  rad_install_missing "${rad_run_packages[@]}" || return
  if [ -f "$BUILD/CMakeCache.txt" ]; then
    rad_configure || return
  else
    rad_configure -DRAD_BUILD_TESTS=OFF -DRAD_BUILD_BENCH=OFF || return
  fi
  cmake --build "$BUILD" -j "$(nproc)" --target "$@"
}

rad_configure() {  # [-DOPTION=VALUE...]: configures $BUILD (a second when nothing changed)
  local extra=()
  if [[ "$RAD_SANITIZE" == *thread* ]]; then
    local deps
    deps="$(rad_tsan_deps)" || return
    extra=(-DCMAKE_PREFIX_PATH="$deps" -DTBB_DIR="$deps/lib/cmake/TBB"
      -Dembree_DIR="$(echo "$deps"/lib/cmake/embree-*)")
    export LD_LIBRARY_PATH="$deps/lib${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}"
  fi
  # Configured every time, so a changed option takes effect.
  cmake -S "$ROOT" -B "$BUILD" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo \
    -DRAD_SANITIZE="$RAD_SANITIZE" "${extra[@]}" "$@" >/dev/null
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
rad_install_web() {  # [page]: the page's modules only (three, lil-gui), not its test's browser
  rad_install_missing libcpp-httplib-dev || echo "warning: could not install libcpp-httplib-dev"
  command -v npm >/dev/null 2>&1 || rad_install_missing nodejs npm || true
  if [ "${1:-}" != page ] && [ ! -x /usr/bin/chromium ]; then
    rad_install_missing chromium || echo "warning: could not install chromium"
  fi
  command -v npm >/dev/null 2>&1 || { echo "warning: npm missing: rad serve has no page"; return 0; }
  local web="$BUILD/web"
  local whole=1  # whether every module of package.json is installed at its version
  if ! cmp -s "$ROOT/tools/e2e/package.json" "$web/package.json" ||
      [ ! -d "$web/node_modules/playwright-core" ]; then
    whole=0
  fi
  if [ "${1:-}" = page ]; then
    # three and lil-gui at package.json's versions, recorded in page-modules.txt.
    local modules
    modules="$(node -e 'const d = require(process.argv[1]).dependencies;
      console.log(["three", "lil-gui"].map((n) => n + "@" + d[n]).join(" "))' \
      "$ROOT/tools/e2e/package.json")" || { echo "warning: cannot read tools/e2e/package.json"; return 0; }
    if ((whole)) && [ -f "$web/node_modules/three/build/three.module.js" ] &&
        [ -f "$web/node_modules/lil-gui/dist/lil-gui.esm.min.js" ]; then
      return 0
    fi
    if [ "$(cat "$web/page-modules.txt" 2>/dev/null)" = "$modules" ] &&
        [ -f "$web/node_modules/three/build/three.module.js" ] &&
        [ -f "$web/node_modules/lil-gui/dist/lil-gui.esm.min.js" ]; then
      return 0
    fi
    mkdir -p "$web"
    rm -f "$web/package.json" "$web/package-lock.json"  # or npm would install all of it
    # shellcheck disable=SC2086
    if npm install --prefix "$web" --no-save --no-audit --no-fund --loglevel=error $modules >/dev/null
    then
      echo "$modules" >"$web/page-modules.txt"
    else
      echo "warning: could not install $modules"
    fi
    return 0
  fi
  if ((whole == 0)) ||
      [ ! -f "$web/node_modules/three/build/three.module.js" ] ||
      [ ! -f "$web/node_modules/lil-gui/dist/lil-gui.esm.min.js" ] ||
      [ ! -d "$web/node_modules/playwright-core" ]; then
    mkdir -p "$web"
    cp "$ROOT/tools/e2e/package.json" "$web/package.json"
    npm install --prefix "$web" --no-audit --no-fund --loglevel=error >/dev/null ||
      echo "warning: could not install three, lil-gui and playwright-core"
  fi
}
