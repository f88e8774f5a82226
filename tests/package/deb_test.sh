#!/bin/sh
# The .debs CPack builds, checked as their files will land: unpacked into temporary roots
# (dpkg-deb -x), their control fields read (dpkg-deb -f):
#   - exactly two packages: vmass (daemon, tools, unit, examples, man pages, completion, the
#     Python and Java types) and vmass-dev (headers, static libraries and the CMake package in
#     the multiarch directory), each file in one of them; vmass-dev depends on the same vmass,
#     and an outside project builds against it alone (find_package(vmass), vmass::config)
#   - vmassd --version runs from the unpacked vmass and vmass-can check passes on the installed
#     example's DBC; the unit, the example config and the Python types are where Debian keeps them
#   - man pages gzipped without name or time stamp (gzip -9n); a DEP-5 copyright and a changelog
#     whose version is the package's in both /usr/share/doc directories; while the source tree
#     has a LICENSE or COPYING file, the copyright may not say that vmass states no license
#   - the maintainer scripts, run with stand-ins for deb-systemd-helper, deb-systemd-invoke and
#     systemctl: an installation neither enables nor starts vmassd (docs/vehicle-install.md:
#     configure, then `systemctl enable --now vmassd`), an upgrade try-restarts it, a removal
#     stops it, a purge forgets its enablement state
#   - lintian (Debian's policy checker) on both packages: no error, no warning that the package
#     does not override (/usr/share/lintian/overrides/PACKAGE, each override with its reason)
#   deb_test.sh BUILD_DIR VERSION OUT_DIR SOURCE_DIR
set -u
build=$1
version=$2
out=$3
source=$4
fail() { echo "FAIL: $*"; exit 1; }

rm -rf "$out" && mkdir -p "$out" || exit 1
cpack --config "$build/CPackConfig.cmake" -B "$out" >"$out/cpack.log" 2>&1 ||
  fail "cpack: $(tail -20 "$out/cpack.log")"
deb=$(ls "$out"/vmass_"$version"_*.deb 2>/dev/null | head -1)
dev=$(ls "$out"/vmass-dev_"$version"_*.deb 2>/dev/null | head -1)
[ -n "$deb" ] || fail "no vmass_${version}_*.deb: $(ls "$out")"
[ -n "$dev" ] || fail "no vmass-dev_${version}_*.deb: $(ls "$out")"
# A third package would be an install() rule in an unexpected component.
[ "$(ls "$out"/*.deb | wc -l)" = 2 ] || fail "not two packages: $(ls "$out"/*.deb)"

depends=$(dpkg-deb -f "$deb" Depends)
for dep in liblcm1 libyaml-cpp libspdlog libsystemd0 python3-matplotlib; do
  echo "$depends" | grep -q "$dep" || fail "Depends lacks $dep: $depends"
done
dpkg-deb -f "$deb" Recommends | grep -q "bash-completion" ||
  fail "vmass does not recommend bash-completion: $(dpkg-deb -f "$deb" Recommends)"
dev_depends=$(dpkg-deb -f "$dev" Depends)
for dep in "vmass (= $version)" libeigen3-dev libboost-dev libyaml-cpp-dev liblcm-dev; do
  echo "$dev_depends" | grep -qF "$dep" || fail "vmass-dev's Depends lacks $dep: $dev_depends"
done

root=$out/root
devroot=$out/devroot
dpkg-deb -x "$deb" "$root" || fail "dpkg-deb -x $deb"
dpkg-deb -x "$dev" "$devroot" || fail "dpkg-deb -x $dev"
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

# The split: development files in vmass-dev only, programs in vmass only.
multiarch=$(dpkg-architecture -qDEB_HOST_MULTIARCH) || fail "dpkg-architecture"
libdir=$devroot/usr/lib/$multiarch
[ -f "$libdir/cmake/vmass/vmassConfig.cmake" ] || fail "no CMake package in $libdir/cmake/vmass"
for lib in core can config io; do
  [ -f "$libdir/libvmass_$lib.a" ] || fail "no libvmass_$lib.a in $libdir: $(ls "$libdir")"
done
for header in core/pipeline.hpp can/dbc.hpp config/config.hpp io/regular_file.hpp version.hpp \
    lcmtypes/vmass/status_t.hpp; do
  [ -f "$devroot/usr/include/vmass/$header" ] || fail "vmass-dev lacks $header"
done
stray=$(cd "$root" && find . \( -path ./usr/include -o -name '*.a' -o -path '*/cmake/vmass' \) \
  -print)
[ -z "$stray" ] || fail "development files in vmass: $stray"
stray=$(cd "$devroot" && find . -type f ! -path ./usr/include/\* ! -path "./usr/lib/$multiarch/*" \
  ! -path ./usr/share/doc/vmass-dev/\* -print)
[ -z "$stray" ] || fail "vmass-dev holds more than development files: $stray"

# vmass-dev as a team uses it: tests/package/outside built against the unpacked package alone,
# loading the unpacked vmass's example config and a broken copy of it.
cmake -S "$source/tests/package/outside" -B "$out/outside" -G Ninja \
  -DCMAKE_PREFIX_PATH="$devroot/usr" -DCMAKE_EXE_LINKER_FLAGS="${OUTSIDE_LDFLAGS:-}" \
  >"$out/outside.log" 2>&1 ||
  fail "find_package(vmass) in vmass-dev: $(tail -20 "$out/outside.log")"
grep -q "vmass_DIR:PATH=$libdir/cmake/vmass" "$out/outside/CMakeCache.txt" ||
  fail "not vmass-dev's CMake package: $(grep vmass_DIR "$out/outside/CMakeCache.txt")"
cmake --build "$out/outside" >>"$out/outside.log" 2>&1 ||
  fail "build against vmass-dev: $(tail -20 "$out/outside.log")"
sed 's/^\(  empty_mass_kg:\) .*/\1 heavy/' "$examples/vmassd.example.yaml" >"$out/broken.yaml"
"$out/outside/outside" "$examples/vmassd.example.yaml" "$out/broken.yaml" >"$out/outside.txt" &&
  grep -q "^config: empty mass [0-9]" "$out/outside.txt" &&
  grep -q "^broken: $out/broken.yaml:[0-9]*: vehicle.empty_mass_kg: " "$out/outside.txt" ||
  fail "the outside project against vmass-dev: $(cat "$out/outside.txt")"

# Man pages: gzipped with -9n (no name, no time stamp: reproducible), none uncompressed.
pages=0
for page in "$root"/usr/share/man/man1/*; do
  case $page in
    *.1.gz) ;;
    *) fail "not a gzipped page: $page" ;;
  esac
  gzip -t "$page" || fail "corrupt $page"
  # gzip header bytes 3-7: flags (no FNAME) and mtime, all zero under -n.
  [ "$(od -An -tx1 -j3 -N5 "$page" | tr -d ' \n')" = 0000000000 ] ||
    fail "$page keeps a name or a time stamp (gzip -9n)"
  pages=$((pages + 1))
done
[ -f "$root/usr/share/man/man1/vmassd.1.gz" ] || fail "no vmassd.1.gz"
zcat "$root/usr/share/man/man1/vmassd.1.gz" | grep -q "replay a CAN log" ||
  fail "vmassd.1.gz lacks --replay"

# Copyright (DEP-5) and changelog in both packages.
for doc in "$root/usr/share/doc/vmass" "$devroot/usr/share/doc/vmass-dev"; do
  dep5=https://www.debian.org/doc/packaging-manuals/copyright-format/1.0/
  [ "$(head -1 "$doc/copyright")" = "Format: $dep5" ] ||
    fail "$doc/copyright is not DEP-5: $(head -1 "$doc/copyright")"
  zcat "$doc/changelog.gz" >"$out/changelog" || fail "$doc/changelog.gz"
  logged=$(dpkg-parsechangelog -l "$out/changelog" -S Version) || fail "dpkg-parsechangelog"
  [ "$logged" = "$version" ] ||
    fail "$doc/changelog.gz's last entry is $logged, the package $version (packaging/debian)"
done
for license in LICENSE LICENSE.md LICENSE.txt COPYING; do
  if [ -f "$source/$license" ] && grep -q "not-yet-licensed" "$root/usr/share/doc/vmass/copyright"
  then
    fail "the source tree has $license: packaging/debian/copyright must state its terms"
  fi
done

# Maintainer scripts, with stand-ins that log their arguments; /run/systemd/system (systemd
# running) pointed at a directory of ours in a copy of each script.
control=$out/control
dpkg-deb -e "$deb" "$control" || fail "dpkg-deb -e"
fake=$out/fake
mkdir -p "$fake/bin" "$fake/systemd-running/run/systemd/system" "$fake/no-systemd"
for tool in deb-systemd-helper deb-systemd-invoke systemctl; do
  cat >"$fake/bin/$tool" <<EOF
#!/bin/sh
echo "$tool \$*" >>"$fake/calls"
case "\$*" in
  *debian-installed*) [ -f "$fake/installed" ] ;;
  *was-enabled*) [ -f "$fake/enabled" ] ;;
esac
EOF
  chmod +x "$fake/bin/$tool"
done
# run SCRIPT SYSTEMD(systemd-running|no-systemd) ARGS...: $calls, the calls it made, one a line
run() {
  script=$1 systemd=$2
  shift 2
  [ -x "$control/$script" ] || fail "no executable $script in vmass"
  sed "s|/run/systemd/system|$fake/$systemd/run/systemd/system|g" "$control/$script" \
    >"$fake/$script"
  rm -f "$fake/calls" && touch "$fake/calls"
  PATH=$fake/bin:$PATH sh "$fake/$script" "$@" || fail "$script $*: exit $?"
  calls=$(cat "$fake/calls")
}
rm -f "$fake/installed" "$fake/enabled"
run postinst systemd-running configure ""
echo "$calls" | grep -Eq "(enable|start|restart)( |$)" &&
  fail "postinst enables or starts vmassd on installation: $calls"
echo "$calls" | grep -q "^deb-systemd-helper update-state vmassd.service$" ||
  fail "postinst does not record the unit's state: $calls"
echo "$calls" | grep -q "^systemctl --system daemon-reload$" ||
  fail "postinst does not reload systemd: $calls"
run postinst no-systemd configure ""
echo "$calls" | grep -q "^systemctl" && fail "postinst calls systemctl without systemd: $calls"
touch "$fake/installed" "$fake/enabled"
run postinst systemd-running configure 0.0.9
echo "$calls" | grep -q "^deb-systemd-helper enable vmassd.service$" ||
  fail "an upgrade does not keep an enabled vmassd enabled: $calls"
echo "$calls" | grep -q "^deb-systemd-invoke try-restart vmassd.service$" ||
  fail "an upgrade does not restart a running vmassd: $calls"
echo "$calls" | grep -q "invoke start" && fail "an upgrade starts a stopped vmassd: $calls"
run prerm systemd-running remove
[ "$calls" = "deb-systemd-invoke stop vmassd.service" ] || fail "prerm remove: $calls"
run prerm systemd-running upgrade 0.1.1
[ -z "$calls" ] || fail "prerm upgrade: $calls"
run postrm systemd-running remove
[ "$calls" = "systemctl --system daemon-reload" ] || fail "postrm remove: $calls"
if [ -x /usr/bin/deb-systemd-helper ]; then  # the script's own guard
  run postrm no-systemd purge
  [ "$calls" = "deb-systemd-helper purge vmassd.service" ] || fail "postrm purge: $calls"
fi

# lintian: no error, no warning left unexplained.
command -v lintian >/dev/null || fail "lintian is not installed (scripts/install-deps.sh)"
lintian --fail-on error,warning --show-overrides --tag-display-limit 0 "$deb" "$dev" \
  >"$out/lintian.txt" 2>&1
rc=$?
errors=$(grep -c '^E: ' "$out/lintian.txt")
warnings=$(grep -c '^W: ' "$out/lintian.txt")
overridden=$(grep -c '^O: ' "$out/lintian.txt")
[ "$rc" = 0 ] && [ "$errors" = 0 ] && [ "$warnings" = 0 ] ||
  fail "lintian (exit $rc): $errors errors, $warnings warnings:
$(grep -v '^running with root' "$out/lintian.txt")"
echo "ok: $(basename "$deb"): $(du -k "$deb" | cut -f1) KiB, $pages man pages; Depends: $depends"
echo "ok: $(basename "$dev"): $(du -k "$dev" | cut -f1) KiB; Depends: $dev_depends"
echo "ok: lintian: 0 errors, 0 warnings, $overridden overridden ($out/lintian.txt)"
