#!/bin/sh
# `cmake --install` of the build, as a team would use it:
#   - a tiny outside project finds the package (find_package(vmass)), links vmass::core and
#     vmass::can, builds and runs
#   - the Python types land where the prefix's Python looks: for /usr/local Debian's Python
#     searches /usr/local/lib/python3.X/dist-packages, not .../python3/dist-packages
#   - the man pages and bash completion are installed, and completion completes an option
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
"$out/outside/outside" >"$out/outside.txt" || fail "outside program: $(cat "$out/outside.txt")"
grep -q "speed 100.0 km/h, estimator " "$out/outside.txt" || fail "$(cat "$out/outside.txt")"
echo "ok: an outside project built against find_package(vmass): $(cat "$out/outside.txt")"

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
  [ -s "$prefix/share/man/man1/$tool.1" ] || fail "no man page for $tool"
  [ -s "$prefix/share/bash-completion/completions/$tool" ] || fail "no completion for $tool"
done
installed=0
for program in "$prefix"/bin/*; do
  tool=$(basename "$program")
  [ -x "$program" ] || fail "$tool installed without its run bit: $(ls -l "$program")"
  [ -s "$prefix/share/man/man1/$tool.1" ] || fail "no man page for the installed $tool"
  [ -s "$prefix/share/bash-completion/completions/$tool" ] || fail "no completion for $tool"
  installed=$((installed + 1))
done
for tool in vmass-suite vmass-accuracy-report vmass-bench vmass-bench-daemon vmass-soak; do
  [ ! -e "$prefix/bin/$tool" ] || fail "$tool is a build-tree tool, installed"
done
[ "$installed" -ge 12 ] || fail "$installed programs installed: $(ls "$prefix/bin")"
grep -q "replay a CAN log" "$prefix/share/man/man1/vmassd.1" || fail "vmassd.1 lacks --replay"
words=$(PATH=$prefix/bin:$PATH bash -c '
  . "$1/share/bash-completion/completions/vmass-replay"
  COMP_WORDS=(vmass-replay --tr); COMP_CWORD=1; _vmass_complete; echo "${COMPREPLY[*]}"' \
  sh "$prefix")
[ "$words" = "--truth" ] || fail "completion of 'vmass-replay --tr': '$words'"
echo "ok: $installed programs, each executable with its man page and bash completion"
