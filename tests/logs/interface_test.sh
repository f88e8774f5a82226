#!/bin/sh
# One interface of a multi-interface log in the formats written by independent writers
# (python-can: ASC, BLF, TRC; asammdf: MDF4), MDF4 through vmass-log-convert: a part of
# the golden drive on can1 (channel, bus 2) with noise frames of the same ids on can0 (channel,
# bus 1). vmass-replay --interface can1 gives in every format the estimate it gives for the
# candump -l log; a name the log does not have is exit 2 with the interfaces it has, numbered
# as in every format: channel (bus) N is can<N-1>. Skipped (77) without the venv of
# scripts/install-python-deps.sh.
#   interface_test.sh BIN_DIR PYTHON GOLDEN_CAN_DIR OUT_DIR
set -u
here=$(cd "$(dirname "$0")" && pwd)
bin=$1
python=$2
golden=$3
out=$4
fail() { echo "FAIL: $*"; exit 1; }

if ! "$python" -c "import can, asammdf" 2>/dev/null; then
  echo "skip: $python lacks python-can or asammdf (scripts/install-python-deps.sh)"
  exit 77  # ctest's SKIP_RETURN_CODE
fi
rm -rf "$out" && mkdir -p "$out" || exit 1
cd "$out" || exit 1
tar -xJf "$golden/golden_can.tar.xz" drive.log || fail "cannot extract the golden drive"
config=$golden/config.yaml
head -n 30000 drive.log |
  awk '{ l = $0; sub(/ can0 /, " can1 ", l); print l
         if (NR % 3 == 0) { sub(/#.*/, "#FFFFFFFFFFFFFFFF"); print } }' >mixed.log
TZ=UTC "$python" "$here/write_logs.py" mixed.log x >/dev/null || fail "write_logs.py"

replay() { "$bin/vmass-replay" --config "$config" "$@"; }
replay --log mixed.log --interface can1 --out candump.csv >/dev/null 2>candump.err ||
  fail "candump -l: $(cat candump.err)"
for ext in asc blf trc mf4; do
  replay --log x/drive.$ext --interface can1 --out $ext.csv >/dev/null 2>$ext.err ||
    fail "$ext: --interface can1: $(cat $ext.err)"
  grep -q "drive.$ext (.*): 30000 frames on can1, 10000 frames of other interfaces skipped, 0 corrupt" \
    $ext.err || fail "$ext: the report: $(cat $ext.err)"
  cmp -s candump.csv $ext.csv || fail "$ext: the estimate differs from the candump log's"
  replay --log x/drive.$ext --interface can2 >/dev/null 2>${ext}_none.err
  rc=$?
  [ $rc -eq 2 ] || fail "$ext: --interface can2: exit $rc, expected 2"
  grep -q "drive.$ext: no frame on interface can2; the log has can1 (30000 frames), can0 (10000 frames)" \
    ${ext}_none.err || fail "$ext: no frame on can2: $(cat ${ext}_none.err)"
  echo "ok: $ext: --interface can1 as for the candump log; can2 refused with the interfaces"
done
