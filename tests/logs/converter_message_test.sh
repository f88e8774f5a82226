#!/bin/sh
# What a system without the Python packages is told, as an installed vmass tells it: MDF4 is
# read through vmass-log-convert (asammdf, which Debian does not package), BLF natively.
#   - vmass-replay / vmass-can decode read a BLF log with neither the converter nor Python there
#   - an MDF4 log through the installed converter on /usr/bin/python3 without asammdf is exit 2
#     with how to install it on an installed system (a venv, pip install asammdf,
#     VMASS_PYTHON), never a path in a source tree; the build tree's copy adds the source
#     tree's way
#   converter_message_test.sh BIN_DIR INSTALLED_CONVERTER OUT_DIR
set -u
bin=$1
installed=$2
out=$3
fail() { echo "FAIL: $*"; exit 1; }

rm -rf "$out" && mkdir -p "$out" || exit 1
cd "$out" || exit 1
printf 'VERSION ""\n' >empty.dbc

# A BLF log of one frame (a stored container), laid out by hand.
python3 - <<'PY' || fail "writing the BLF log"
import struct
o = struct.pack("<4sHHLL", b"LOBJ", 32, 1, 48, 1) + struct.pack("<LHHQ", 2, 0, 0, 1500000)
o += struct.pack("<HBBL8s", 1, 0, 2, 0x123, b"\xde\xad")
c = struct.pack("<4sHHLL", b"LOBJ", 16, 1, 32 + len(o), 10) + struct.pack("<H6xL4x", 0, len(o)) + o
st = (2021, 6, 2, 1, 8, 0, 0, 0)
h = struct.pack("<4sLBBBBBBBBQQLL8H8H", b"LOGG", 144, 5, 0, 0, 0, 2, 6, 8, 1, 144 + len(c),
                144 + len(c), 1, 0, *st, *st)
open("drive.blf", "wb").write(h + b"\0" * (144 - len(h)) + c)
PY
VMASS_LOG_CONVERT=/nonexistent/vmass-log-convert VMASS_PYTHON=/nonexistent/python \
  "$bin/vmass-can" decode --dbc empty.dbc drive.blf >blf.out 2>blf.err ||
  fail "BLF without converter and Python: $(cat blf.err)"
[ "$(cat blf.out)" = "(1622534400.001500) can0 123#DEAD" ] || fail "BLF frames: $(cat blf.out)"
echo "ok: BLF read without vmass-log-convert and without Python"

printf 'MDF     4.10    \000\000\000\000' >drive.mf4
if /usr/bin/python3 -c "import asammdf" 2>/dev/null; then
  echo "skip: /usr/bin/python3 has asammdf: the missing-package message is not tested"
  exit 77
fi
# (The installed copy gets its execute bit when installed: run by its interpreter line's Python.)
VMASS_PYTHON=/usr/bin/python3 VMASS_LOG_CONVERT="$installed" "$bin/vmass-can" decode \
  --dbc empty.dbc drive.mf4 >/dev/null 2>installed.err
rc=$?
[ $rc -eq 2 ] || fail "MDF4 without asammdf (installed converter): exit $rc: $(cat installed.err)"
for want in "reading MDF4 needs the Python package asammdf, which /usr/bin/python3 lacks" \
            "Debian has no package of it" "pip install asammdf" "VMASS_PYTHON="; do
  grep -qF "$want" installed.err || fail "the installed message lacks '$want': $(cat installed.err)"
done
! grep -q "scripts/" installed.err || fail "the installed message names a source tree: $(cat installed.err)"
echo "ok: installed: $(grep -F "needs the Python package" installed.err)"

# The build tree's copy, its venv not tried (as when the venv lacks the package too).
env -u VMASS_PYTHON VMASS_LOG_CONVERT_FALLBACK=1 "$bin/vmass-log-convert" drive.mf4 \
  >/dev/null 2>build.err
rc=$?
[ $rc -eq 2 ] || fail "MDF4 without asammdf (build tree's converter): exit $rc"
grep -qF "pip install asammdf" build.err && grep -qF "scripts/install-python-deps.sh" build.err ||
  fail "the build tree's message: $(cat build.err)"
echo "ok: build tree: $(cat build.err)"
