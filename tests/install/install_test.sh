#!/usr/bin/env bash
# The installed rad works from where it is installed (cmake/packaging.cmake).
#   install_test.sh prefix BUILD VERSION CMAKE   cmake --install into a temporary prefix, then
#                                                 run the installed programs from there
#   install_test.sh deb BUILD VERSION CPACK      cpack -G DEB into a temporary folder, then read
#                                                 the package and run its rad unpacked
# Everything runs from a temporary folder, away from the source and build trees, with
# RAD_WEB_MODULES unset, so nothing is found there by accident. Exit 77: skipped.
set -euo pipefail
mode=$1 build=$2 version=$3 tool=$4
d=$(mktemp -d)
server=""
cleanup() {
  [ -n "$server" ] && kill "$server" 2>/dev/null
  rm -rf "$d"
}
trap cleanup EXIT
unset RAD_WEB_MODULES
fail() { echo "FAIL: $*"; exit 1; }
mkdir "$d/work"
cd "$d/work"

# The page's modules are in the build when rad_install_web put them there (tools/test does).
modules="$build/web/node_modules"
have_modules=0
[ -f "$modules/three/build/three.module.js" ] && [ -f "$modules/lil-gui/dist/lil-gui.esm.min.js" ] &&
  have_modules=1

# ROOT/usr holds an installation: check it and run its programs.
check_installed_tree() {
  local usr=$1/usr
  for f in bin/rad bin/rad-gen lib/rad/rad share/man/man1/rad.1.gz share/man/man1/rad-gen.1.gz \
      share/doc/rad/README.md \
      share/doc/rad/docs/options.md share/doc/rad/docs/install.md \
      share/rad/scenes/cornell_box.des share/rad/scenes/original_style.des \
      share/rad/scenes/off/floor.off; do
    [ -e "$usr/$f" ] || fail "not installed: $f"
  done
  [ -L "$usr/bin/rad" ] || fail "bin/rad is not a link to lib/rad/rad"
  [ "$(readlink -f "$usr/bin/rad")" = "$(readlink -f "$usr/lib/rad/rad")" ] ||
    fail "bin/rad leads to $(readlink -f "$usr/bin/rad"), not lib/rad/rad"
  [ ! -e "$usr/share/rad/scenes/bad" ] || fail "the malformed test scenes were installed"

  local got
  got=$("$usr/bin/rad" --version) || fail "installed rad --version failed"
  [ "$got" = "rad $version" ] || fail "installed rad --version printed '$got', not 'rad $version'"
  echo "installed rad --version: $got"

  # The manual page carries the same version and formats without a warning.
  local page warnings
  for page in rad rad-gen; do
    gzip -dc "$usr/share/man/man1/$page.1.gz" |
      grep -q "^\.TH [A-Z\\-]* 1 \"[^\"]*\" \"rad $version\"" ||
      fail "the installed $page.1's .TH line does not say rad $version"
    if command -v groff >/dev/null; then
      warnings=$(gzip -dc "$usr/share/man/man1/$page.1.gz" | groff -man -Tutf8 -ww -z 2>&1)
      [ -z "$warnings" ] || fail "groff warns on the installed $page.1: $warnings"
    fi
  done

  # A bundled scene checked, and one solved and rendered from its installed OFF files.
  "$usr/bin/rad" --check "$usr/share/rad/scenes/cornell_box.des" >check.txt ||
    fail "installed rad --check on the installed Cornell box failed: $(cat check.txt)"
  "$usr/bin/rad" -q --max-shots 3 --size 64x64 "$usr/share/rad/scenes/original_style.des" \
    room.ply --image room.png || fail "installed rad could not solve the installed original_style.des"
  [ -s room.ply ] || fail "no room.ply"
  [ "$(head -c 8 room.png | od -An -tx1 | tr -d ' \n')" = 89504e470d0a1a0a ] ||
    fail "room.png is not a PNG"
  head -c 3 room.ply | grep -q ply || fail "room.ply is not a PLY"
  echo "installed rad solved and rendered the installed original_style.des"

  # rad-gen writes a scene the installed rad reads.
  "$usr/bin/rad-gen" cornell gen.des --size 100 >/dev/null || fail "installed rad-gen failed"
  "$usr/bin/rad" --check gen.des >/dev/null 2>&1 || fail "installed rad cannot read rad-gen's scene"
  echo "installed rad-gen wrote a scene rad checks"

  if ((have_modules)); then
    check_page "$usr"
  else
    echo "the build has no page modules ($modules): rad serve's page not checked"
  fi
}

# GET PATH from the server on PORT into FILE (body only); fails unless the status is 200.
http_get() {
  local port=$1 path=$2 out=$3
  exec 3<>"/dev/tcp/127.0.0.1/$port"
  printf 'GET %s HTTP/1.0\r\nHost: 127.0.0.1:%s\r\n\r\n' "$path" "$port" >&3
  cat <&3 >"$out.raw"
  exec 3>&-
  head -1 "$out.raw" | grep -q ' 200 ' || fail "GET $path: $(head -1 "$out.raw")"
  sed '1,/^\r$/d' "$out.raw" >"$out"
}

# The installed rad serve hands out the installed modules, found beside its executable.
check_page() {
  local usr=$1
  "$usr/bin/rad" serve "$usr/share/rad/scenes/cornell_box.des" --port 0 --max-shots 1 \
    --threads 1 >serve.log 2>&1 &
  server=$!
  local port="" i
  for i in $(seq 100); do
    port=$(grep -oE 'http://127\.0\.0\.1:[0-9]+/' serve.log | head -1 | grep -oE '[0-9]+/$' |
      tr -d /) || true
    [ -n "$port" ] && break
    kill -0 "$server" 2>/dev/null || fail "installed rad serve ended: $(cat serve.log)"
    sleep 0.2
  done
  [ -n "$port" ] || fail "installed rad serve printed no address: $(cat serve.log)"
  http_get "$port" / index.html
  grep -qi '<html' index.html || fail "GET / is not the page"
  local pair url m
  for pair in three.module.js=three/build/three.module.js three.core.js=three/build/three.core.js \
      OrbitControls.js=three/examples/jsm/controls/OrbitControls.js \
      lil-gui.esm.js=lil-gui/dist/lil-gui.esm.min.js; do
    url=/vendor/${pair%%=*} m=${pair#*=}
    http_get "$port" "$url" served.js
    cmp -s served.js "$usr/share/rad/web/node_modules/$m" || fail "$url is not the installed $m"
  done
  kill -TERM "$server"
  local status=0
  wait "$server" || status=$?
  server=""
  ((status == 0)) || fail "installed rad serve exited $status on SIGTERM: $(cat serve.log)"
  echo "installed rad serve served its page and the installed three.js and lil-gui"
}

case $mode in
  prefix)
    "$tool" --install "$build" --prefix "$d/root/usr" >install.log 2>&1 ||
      fail "cmake --install failed: $(cat install.log)"
    check_installed_tree "$d/root"
    ;;
  deb)
    command -v dpkg-deb >/dev/null || { echo "dpkg-deb not installed: skipped"; exit 77; }
    "$tool" --config "$build/CPackConfig.cmake" -G DEB -B "$d/pkg" >cpack.log 2>&1 ||
      fail "cpack -G DEB failed: $(cat cpack.log)"
    debs=("$d"/pkg/rad_"$version"_*.deb)
    [ -f "${debs[0]}" ] || fail "no rad_${version}_*.deb: $(ls "$d/pkg")"
    deb=${debs[0]}
    echo "built $(basename "$deb")"
    [ "$(dpkg-deb -f "$deb" Package)" = rad ] || fail "Package is not rad"
    [ "$(dpkg-deb -f "$deb" Version)" = "$version" ] ||
      fail "Version is $(dpkg-deb -f "$deb" Version), not the project version $version"
    depends=$(dpkg-deb -f "$deb" Depends)
    for lib in libembree3-3 libtbb12 libfmt9 libc6; do
      [[ ", $depends," == *", $lib "* || ", $depends," == *", $lib,"* ]] ||
        fail "Depends does not name $lib: $depends"
    done
    echo "Depends: $depends"
    [ -n "$(dpkg-deb -f "$deb" Maintainer)" ] || fail "no Maintainer"
    dpkg-deb -c "$deb" >contents.txt
    for f in './usr/bin/rad -> ../lib/rad/rad' ./usr/bin/rad-gen ./usr/lib/rad/rad \
        ./usr/share/man/man1/rad.1.gz ./usr/share/man/man1/rad-gen.1.gz \
        ./usr/share/rad/scenes/cornell_box.des \
        ./usr/share/doc/rad/README.md; do
      grep -qF " $f" contents.txt || fail "the package does not hold $f"
    done
    if ((have_modules)); then
      grep -qF ./usr/share/rad/web/node_modules/three/build/three.module.js contents.txt ||
        fail "the package does not hold rad serve's modules"
    fi
    # Would apt install it here (its Depends resolvable)? Only simulated.
    if command -v apt-get >/dev/null; then
      apt-get install -s "$deb" >apt.log 2>&1 || fail "apt-get install -s refuses it: $(cat apt.log)"
      echo "apt-get install -s accepts it"
    fi
    dpkg-deb -x "$deb" "$d/root"
    check_installed_tree "$d/root"
    ;;
  *)
    fail "unknown mode $mode"
    ;;
esac
echo "ok"
