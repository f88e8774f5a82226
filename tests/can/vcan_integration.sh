#!/bin/sh
# vcan integration test of the SocketCAN reader; runs inside tests/can/vcan_vm.sh (real vcan0).
#
#   vcan_integration.sh VMASS_CAN [IFACE]      (IFACE: default vcan0)
#
# Starts `vmass-can dump --can IFACE` (SocketCanReader), sends classic, extended, remote and
# CAN FD frames with cansend and canplayer, takes vcan0 down and up mid-stream (ENETDOWN: the
# reader keeps its socket), then deletes and re-creates vcan0 (ENODEV: the reader re-creates its
# socket by name), and checks that every frame arrived, in order, exactly as candump -L prints
# the same frames (same kernel timestamps, same text). Writes only to $VCAN_VM_OUT.
set -u
tool=$1
iface=${2:-vcan0}
out=${VCAN_VM_OUT:?run me through vcan_vm.sh}
fail() { echo "vcan_integration: FAIL: $*" >&2; echo "--- dump stderr"; cat "$out/dump.err" >&2; exit 1; }
wait_for() {  # wait_for PATTERN FILE SECONDS
  i=0
  while ! grep -q "$1" "$2" 2>/dev/null; do
    i=$((i + 1))
    [ "$i" -le $(($3 * 20)) ] || return 1
    sleep 0.05
  done
}

t0=$(date +%s.%N)
# CAN FD needs the FD MTU; vcan takes a new MTU only while down.
ip link set $iface down && ip link set $iface mtu 72 && ip link set $iface up || fail "$iface setup"

"$tool" dump --can $iface --count 9 --idle-timeout 30 > "$out/got.log" 2> "$out/dump.err" &
dump_pid=$!
candump -L $iface > "$out/candump.log" 2> "$out/candump.err" &
candump_pid=$!
wait_for "listening on $iface" "$out/dump.err" 10 || fail "vmass-can dump did not start"
sleep 0.5

fd_data=$(i=0; while [ $i -lt 64 ]; do printf '%02X' $i; i=$((i + 1)); done)
cansend $iface 123#DEADBEEF || fail "cansend classic"
cansend $iface 1ABCDEF0#0102 || fail "cansend extended"
cansend $iface 321#R || fail "cansend remote"
cansend $iface "7FF##1$fd_data" || fail "cansend FD"
cat > "$out/replay.log" <<EOF
(1700000000.000000) can0 100#0011223344556677
(1700000000.001000) can0 18DAF110#02
(1700000000.002000) can0 200##0000102030405060708090A0B
EOF
canplayer -I "$out/replay.log" $iface=can0 || fail "canplayer"

# Interface down and up again: the reader must keep its socket and go on.
ip link set $iface down
wait_for "interface down" "$out/dump.err" 10 || fail "reader did not see the interface go down"
cansend $iface 111#01 2>/dev/null && fail "cansend worked on a down interface"
ip link set $iface up
sleep 0.2
cansend $iface 456#CAFE || fail "cansend after up"
sleep 0.3
kill "$candump_pid" 2>/dev/null; wait "$candump_pid" 2>/dev/null

# Interface deleted and re-created: the reader must re-create its socket by name.
ip link del $iface
wait_for "interface gone" "$out/dump.err" 10 || fail "reader did not see the interface vanish"
ip link add dev $iface type vcan && ip link set $iface up
wait_for "socket re-created" "$out/dump.err" 10 || fail "reader did not re-create its socket"
cansend $iface 789#01 || fail "cansend after re-create"

wait "$dump_pid"
status=$?
t1=$(date +%s.%N)
echo "--- vmass-can dump got:"; cat "$out/got.log"
echo "--- vmass-can dump stderr:"; cat "$out/dump.err"
[ "$status" -eq 0 ] || fail "vmass-can dump exited $status (fewer than 9 frames?)"

# The frames, without timestamps, in order. Kernels since 6.0 mark received FD frames with
# CANFD_FDF (4) in the flags digit (candump shows 7FF##1 sent as 7FF##5): compare without it.
cut -d' ' -f2- "$out/got.log" | sed -e 's/##4/##0/; s/##5/##1/; s/##6/##2/; s/##7/##3/' \
  > "$out/got.frames"
cat > "$out/want.frames" <<EOF
$iface 123#DEADBEEF
$iface 1ABCDEF0#0102
$iface 321#R
$iface 7FF##1$fd_data
$iface 100#0011223344556677
$iface 18DAF110#02
$iface 200##0000102030405060708090A0B
$iface 456#CAFE
$iface 789#01
EOF
diff "$out/want.frames" "$out/got.frames" || fail "frames differ"

# Byte for byte what candump -L printed for the same frames (kernel timestamps included).
# candump (can-utils 2020.11) may stop when the interface goes down: compare what it printed,
# which must at least cover the seven frames sent before that.
n=$(wc -l < "$out/candump.log")
[ "$n" -ge 7 ] || fail "candump -L printed $n lines, expected at least 7"
head -n "$n" "$out/got.log" | diff "$out/candump.log" - || fail "our lines differ from candump -L"

grep -q " 0 without kernel timestamp" "$out/dump.err" || fail "frames without kernel timestamp"
# Deleting an interface downs it first: ENETDOWN may be seen more than once.
grep -Eq " [1-9][0-9]* interface down" "$out/dump.err" || fail "interface down not counted"
grep -q "1 interface gone" "$out/dump.err" || fail "interface gone not counted once"
grep -q "1 re-opened" "$out/dump.err" || fail "socket not re-opened once"
echo "--- candump -L stderr:"; cat "$out/candump.err"
echo "vcan_integration: PASS in $(awk "BEGIN {printf \"%.1f\", $t1 - $t0}") s inside the VM"
