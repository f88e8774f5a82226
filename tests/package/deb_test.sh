#!/bin/sh
# The .deb CPack builds, checked as its files will land: unpacked into a temporary root
# (dpkg-deb -x), its control fields read (dpkg-deb -f); vmassd --version runs from it and
# vmass-can check passes on the installed example's DBC; the unit, the example config and the
# Python types are where Debian keeps them.
#   deb_test.sh BUILD_DIR VERSION OUT_DIR
set -u
build=$1
version=$2
out=$3
fail() { echo "FAIL: $*"; exit 1; }

rm -rf "$out" && mkdir -p "$out" || exit 1
cpack --config "$build/CPackConfig.cmake" -B "$out" >"$out/cpack.log" 2>&1 ||
  fail "cpack: $(tail -20 "$out/cpack.log")"
deb=$(ls "$out"/vmass_"$version"_*.deb 2>/dev/null | head -1)
[ -n "$deb" ] || fail "no vmass_${version}_*.deb: $(ls "$out")"
depends=$(dpkg-deb -f "$deb" Depends)
for dep in liblcm1 libyaml-cpp libspdlog libsystemd0 python3-matplotlib; do
  echo "$depends" | grep -q "$dep" || fail "Depends lacks $dep: $depends"
done
root=$out/root
dpkg-deb -x "$deb" "$root" || fail "dpkg-deb -x"
"$root/usr/bin/vmassd" --version >"$out/version.txt" || fail "vmassd --version"
[ "$(cat "$out/version.txt")" = "vmassd $version" ] || fail "version: $(cat "$out/version.txt")"
examples=$root/usr/share/doc/vmass/examples
"$root/usr/bin/vmass-can" check --dbc "$examples/demo_vehicle.dbc" >"$out/check.txt" ||
  fail "vmass-can check on the installed example: $(tail -3 "$out/check.txt")"
grep -q "dbc: demo_vehicle.dbc" "$examples/vmassd.example.yaml" || fail "example config"
unit=$root/usr/lib/systemd/system/vmassd.service
grep -q "^ExecStart=/usr/bin/vmassd " "$unit" || fail "unit ExecStart: $(grep ExecStart "$unit")"
grep -q "^RestartPreventExitStatus=2" "$unit" || fail "unit restarts on a config error"
[ -f "$root/usr/lib/python3/dist-packages/vmass/status_t.py" ] || fail "Python types"
[ -f "$root/usr/lib/x86_64-linux-gnu/cmake/vmass/vmassConfig.cmake" ] ||
  [ -f "$root/usr/lib/cmake/vmass/vmassConfig.cmake" ] || fail "CMake package"
[ -f "$root/usr/share/man/man1/vmassd.1" ] || [ -f "$root/usr/share/man/man1/vmassd.1.gz" ] ||
  fail "man page"
echo "ok: $(basename "$deb"): $(du -k "$deb" | cut -f1) KiB; Depends: $depends"
