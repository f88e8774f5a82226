#!/bin/sh
# `cmake --install` of the build, as a team would use it:
#   - a tiny outside project finds the package (find_package(vmass)), links vmass::core,
#     vmass::can and vmass::config, builds and runs: it decodes a frame and ticks the estimator,
#     loads the installed example config (its empty mass, its estimator) and names the file,
#     line and key of a broken copy of it
#   - libraries and the CMake package are in the multiarch directory (lib/x86_64-linux-gnu)
#   - the Python types land where the prefix's Python looks: for /usr/local Debian's Python
#     searches /usr/local/lib/python3.X/dist-packages, not .../python3/dist-packages
#   - the man pages (gzipped) and bash completion are installed, and completion completes an
#     option
#   - every installed program is executable and has its man page and completion; the build
#     tree's own tools (the suite, its report, the benchmarks) are not installed
#   install_test.sh BUILD_DIR SOURCE_DIR OUT_DIR
set -u
build=$1
source=$2
out=$3
fail() { echo "FAIL: $*"; exit 1; }

rm -rf "$out" && mkdir -p "$out" || exit 1
DESTDIR=$out/root cmake --install "$build" --prefix /usr/local >"$out/install.log" 2>&1 ||
  fail "install: $(tail -5 "$out/install.log")"
prefix=$out/root/usr/local

# A sanitizer build installs instrumented static libraries: the outside project links with
# the same -fsanitize flags (OUTSIDE_LDFLAGS, set by tests/package/CMakeLists.txt).
cmake -S "$source/tests/package/outside" -B "$out/outside" -G Ninja \
  -DCMAKE_PREFIX_PATH="$prefix" -DCMAKE_EXE_LINKER_FLAGS="${OUTSIDE_LDFLAGS:-}" \
  >"$out/outside.log" 2>&1 ||
  fail "find_package(vmass): $(tail -20 "$out/outside.log")"
cmake --build "$out/outside" >>"$out/outside.log" 2>&1 || fail "build: $(tail -20 "$out/outside.log")"
multiarch=$(dpkg-architecture -qDEB_HOST_MULTIARCH) || fail "dpkg-architecture"
[ -f "$prefix/lib/$multiarch/cmake/vmass/vmassConfig.cmake" ] &&
  [ -f "$prefix/lib/$multiarch/libvmass_config.a" ] ||
  fail "no CMake package or libvmass_config.a in $prefix/lib/$multiarch: $(ls -R "$prefix/lib")"
# The installed example config with another empty mass and estimator, and a copy of that whose
# empty mass is a word.
example=$prefix/share/doc/vmass/examples/vmassd.example.yaml
sed -e 's/^\(  empty_mass_kg:\) .*/\1 1733.5/' -e 's/^\(  type:\) bayes /\1 rls   /' \
  "$example" >"$out/vehicle.yaml" || exit 1
grep -q "^  empty_mass_kg: 1733.5$" "$out/vehicle.yaml" &&
  grep -q "^  type: rls " "$out/vehicle.yaml" || fail "no empty_mass_kg or type: bayes in $example"
sed 's/^\(  empty_mass_kg:\) .*/\1 heavy/' "$out/vehicle.yaml" >"$out/broken.yaml" || exit 1
line=$(grep -n "^  empty_mass_kg: heavy$" "$out/broken.yaml" | cut -d: -f1)
"$out/outside/outside" "$out/vehicle.yaml" "$out/broken.yaml" >"$out/outside.txt" ||
  fail "outside program: $(cat "$out/outside.txt")"
grep -q "^speed 100.0 km/h, estimator " "$out/outside.txt" || fail "$(cat "$out/outside.txt")"
grep -qx "config: empty mass 1733.5 kg, estimator rls" "$out/outside.txt" ||
  fail "not the config's empty mass and estimator: $(cat "$out/outside.txt")"
grep -q "^broken: $out/broken.yaml:$line: vehicle.empty_mass_kg: " "$out/outside.txt" ||
  fail "broken config's error, at line $line: $(cat "$out/outside.txt")"
echo "ok: an outside project built against find_package(vmass):"
sed 's/^/  /' "$out/outside.txt"

site=$(/usr/bin/python3 -c 'import sys; print(" ".join(sys.path))')
found=""
for dir in $site; do
  case $dir in
    /usr/local/*) [ -f "$out/root$dir/vmass/status_t.py" ] && found=$dir ;;
  esac
done
[ -n "$found" ] || fail "no vmass under a /usr/local directory of sys.path ($site): \
$(find "$out/root" -name status_t.py)"
PYTHONPATH=$out/root$found /usr/bin/python3 -c "import vmass; vmass.status_t()" ||
  fail "the installed types do not import"
echo "ok: Python types in $found, on Debian's sys.path for /usr/local"

for tool in vmassd vmass-replay vmass-can vmass-plot; do
  [ -s "$prefix/share/man/man1/$tool.1.gz" ] || fail "no man page for $tool"
  [ -s "$prefix/share/bash-completion/completions/$tool" ] || fail "no completion for $tool"
done
installed=0
for program in "$prefix"/bin/*; do
  tool=$(basename "$program")
  [ -x "$program" ] || fail "$tool installed without its run bit: $(ls -l "$program")"
  [ -s "$prefix/share/man/man1/$tool.1.gz" ] || fail "no man page for the installed $tool"
  [ -s "$prefix/share/bash-completion/completions/$tool" ] || fail "no completion for $tool"
  installed=$((installed + 1))
done
for tool in vmass-suite vmass-accuracy-report vmass-bench vmass-bench-daemon vmass-soak; do
  [ ! -e "$prefix/bin/$tool" ] || fail "$tool is a build-tree tool, installed"
done
[ "$installed" -ge 12 ] || fail "$installed programs installed: $(ls "$prefix/bin")"
zcat "$prefix/share/man/man1/vmassd.1.gz" | grep -q "replay a CAN log" ||
  fail "vmassd.1.gz lacks --replay"
words=$(PATH=$prefix/bin:$PATH bash -c '
  . "$1/share/bash-completion/completions/vmass-replay"
  COMP_WORDS=(vmass-replay --tr); COMP_CWORD=1; _vmass_complete; echo "${COMPREPLY[*]}"' \
  sh "$prefix")
[ "$words" = "--truth" ] || fail "completion of 'vmass-replay --tr': '$words'"
echo "ok: $installed programs, each executable with its man page and bash completion"
