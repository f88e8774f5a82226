#!/bin/bash
# systemd_vm.sh: run one command on a machine booted with systemd as PID 1 and a real SocketCAN
# stack, from a host (a container) that has neither. vmass's own copy of the recipe, used by the
# systemd service test (tests/service/vmassd_systemd_test.sh).
#
#   systemd_vm.sh [--ifaces can0,vcan1] [--out DIR] [--timeout SECONDS] [--mem MB] -- COMMAND [ARG...]
#
# How: Debian's stock kernel boots under qemu (TCG software emulation; multi-user.target in about
# 40 s). An initramfs (busybox) loads virtio-9p, CAN and overlayfs modules, mounts the host's root
# read-only over 9p and puts a tmpfs copy-on-write overlay over each top-level folder, then hands
# over to the host's own systemd. So inside, everything is writable and nothing written reaches
# the host: `cmake --install --prefix /usr`, `systemctl`, `journalctl`, StateDirectory= and
# DynamicUser= behave as on a vehicle PC. The vcan interfaces named by --ifaces (default can0)
# are up and loopback has a multicast route (LCM) before COMMAND runs, as root, in the current
# folder, from a oneshot unit ordered after multi-user.target; the machine powers off after it.
# The only folder shared back is $VMTEST_OUT, the --out folder (default: a temporary one,
# deleted afterwards), at the same path on both sides. COMMAND's output is printed afterwards
# and its exit status becomes ours (124: --timeout passed).
#
# The first run installs qemu-system-x86, busybox-static, cpio and kmod with apt-get (root) and
# unpacks the current linux-image package into ${VCAN_VM_CACHE:-~/.cache/vcan-vm} (shared with
# tests/can/vcan_vm.sh).
set -euo pipefail

ifaces=can0 timeout=300 mem=1536 out=
while [ $# -gt 0 ]; do
  case "$1" in
    --ifaces) ifaces=$2; shift 2 ;;
    --timeout) timeout=$2; shift 2 ;;
    --mem) mem=$2; shift 2 ;;
    --out) out=$2; shift 2 ;;
    --) shift; break ;;
    -h|--help) sed -n '2,22p' "$0"; exit 0 ;;
    *) echo "systemd_vm.sh: unknown option $1 (see --help)" >&2; exit 2 ;;
  esac
done
[ $# -gt 0 ] || { echo "systemd_vm.sh: no command given (see --help)" >&2; exit 2; }

cache=${VCAN_VM_CACHE:-$HOME/.cache/vcan-vm}
mkdir -p "$cache"

need=()
for p in qemu-system-x86_64:qemu-system-x86 busybox:busybox-static cpio:cpio depmod:kmod; do
  command -v "${p%%:*}" >/dev/null 2>&1 || [ -x "/sbin/${p%%:*}" ] || need+=("${p#*:}")
done
if [ ${#need[@]} -gt 0 ]; then
  echo "systemd_vm.sh: installing ${need[*]}" >&2
  apt-get update -qq >/dev/null && DEBIAN_FRONTEND=noninteractive apt-get install -y -qq "${need[@]}" >/dev/null
fi
busybox=$(command -v busybox || echo /bin/busybox)

# Debian's current kernel, extracted once.
if [ ! -f "$cache/kernel.ok" ]; then
  echo "systemd_vm.sh: fetching Debian's kernel (once)" >&2
  apt-get update -qq >/dev/null || true
  pkg=$(apt-cache depends linux-image-amd64 | awk '/Depends: linux-image-[0-9]/ {print $2; exit}')
  [ -n "$pkg" ] || { echo "systemd_vm.sh: cannot resolve linux-image-amd64" >&2; exit 1; }
  rm -rf "$cache/root" "$cache"/*.deb
  (cd "$cache" && apt-get download "$pkg" >/dev/null 2>&1)
  dpkg-deb -x "$cache"/"$pkg"_*.deb "$cache/root"
  rm -f "$cache"/*.deb
  kver=$(ls "$cache/root/lib/modules")
  PATH=$PATH:/sbin depmod -b "$cache/root" "$kver"
  echo "$kver" > "$cache/kernel.ok"
fi
kver=$(cat "$cache/kernel.ok")
mods=$cache/root/lib/modules/$kver

# The job folder (this side only); the out folder is the same path on both sides.
job=$(mktemp -d "${TMPDIR:-/tmp}/systemd-vm.XXXXXX")
if [ -z "$out" ]; then out=$job/out; fi
mkdir -p "$out"; out=$(cd "$out" && pwd)
trap 'rm -rf "$job"' EXIT
{
  printf 'cd %q || exit 97\n' "$PWD"
  printf 'export VMTEST_OUT=%q HOME=/root PATH=%q\n' "$out" "$PATH"
  printf 'exec >%q/output.txt 2>&1\n' "$out"
  printf 'ip link set lo up; ip link set lo multicast on; ip route add 224.0.0.0/4 dev lo\n'
  printf 'for i in %s; do ip link add dev $i type vcan && ip link set $i up; done\n' "$(echo "$ifaces" | tr , ' ')"
  printf '%q ' "$@"; echo   # bash quoting ($'...' for newlines): run with bash
  printf 'echo $? > %q/.rc\n' "$out"
} > "$job/cmd.sh"

# initramfs: busybox, the modules in dependency order, and an init that runs the job.
ird=$job/initrd; mkdir -p "$ird"/{bin,proc,sys,dev,host,mods}
cp "$busybox" "$ird/bin/busybox"
order=()
for m in virtio_pci 9pnet_virtio 9p can-raw vcan overlay; do
  while read -r _ path _; do order+=("$path"); done < <(PATH=$PATH:/sbin modprobe -d "$cache/root" -S "$kver" --show-depends "$m")
done
names=()
for path in "${order[@]}"; do
  n=$(basename "$path" .ko)
  case " ${names[*]-} " in *" $n "*) continue ;; esac
  cp "$path" "$ird/mods/"; names+=("$n")
done
cat > "$ird/init" <<EOF
#!/bin/busybox sh
B=/bin/busybox
\$B mount -t proc proc /proc; \$B mount -t sysfs sys /sys; \$B mount -t devtmpfs dev /dev
for m in ${names[*]}; do \$B insmod /mods/\$m.ko || echo "systemd_vm.sh: insmod \$m failed"; done
\$B mount -t 9p -o trans=virtio,version=9p2000.L,ro hostroot /host || { echo "systemd_vm.sh: 9p root failed"; \$B poweroff -f; }
\$B mount -t tmpfs -o mode=755 tmpfs /host/run
# /tmp: a fresh tmpfs whose folders are overlays of this machine's (an overlay of /tmp itself
# shows none of its lower folders over 9p)
\$B mkdir -p /hosttmp; \$B mount --bind /host/tmp /hosttmp; \$B mount -t tmpfs -o mode=1777 tmpfs /host/tmp
for d in \$(\$B ls /hosttmp); do
  [ -d /hosttmp/\$d ] && [ ! -L /hosttmp/\$d ] || continue
  \$B mkdir -p /host/tmp/\$d /host/run/.ov/tmp.\$d/u /host/run/.ov/tmp.\$d/w
  \$B mount -t overlay overlay -o lowerdir=/hosttmp/\$d,upperdir=/host/run/.ov/tmp.\$d/u,workdir=/host/run/.ov/tmp.\$d/w /host/tmp/\$d || echo "systemd_vm.sh: overlay /tmp/\$d failed"
done
# every other top-level directory becomes an overlay: this machine's files below, a tmpfs above
for d in \$(\$B ls /host); do
  case \$d in proc|sys|dev|run|tmp|lost+found) continue ;; esac
  [ -d /host/\$d ] && [ ! -L /host/\$d ] || continue
  \$B mkdir -p /host/run/.ov/\$d/u /host/run/.ov/\$d/w
  \$B mount -t overlay overlay -o lowerdir=/host/\$d,upperdir=/host/run/.ov/\$d/u,workdir=/host/run/.ov/\$d/w /host/\$d || echo "systemd_vm.sh: overlay /\$d failed"
done
\$B mkdir -p /host$out
\$B mount -t 9p -o trans=virtio,version=9p2000.L,rw out /host$out || { echo "systemd_vm.sh: 9p out failed"; \$B poweroff -f; }
\$B mkdir -p /host/run/systemd/system/multi-user.target.wants
\$B cp /cmd.sh /host/run/vmtest-cmd.sh
\$B printf '[Unit]\\nDescription=systemd-vm job\\nAfter=multi-user.target\\n[Service]\\nType=oneshot\\nExecStart=/bin/bash /run/vmtest-cmd.sh\\nExecStopPost=/bin/systemctl poweroff -ff\\n' > /host/run/systemd/system/vmtest.service
\$B ln -s ../vmtest.service /host/run/systemd/system/multi-user.target.wants/vmtest.service
\$B umount /proc /sys /dev
exec \$B switch_root /host /lib/systemd/systemd
EOF
chmod +x "$ird/init"; cp "$job/cmd.sh" "$ird/cmd.sh"
(cd "$ird" && find . | cpio -o -H newc 2>/dev/null | gzip -1 > "$job/initrd.gz")

set +e
timeout "$timeout" qemu-system-x86_64 -accel tcg,thread=multi -cpu max -smp 2 -m "$mem" \
  -nic none -nographic -no-reboot -kernel "$cache/root/boot/vmlinuz-$kver" -initrd "$job/initrd.gz" \
  -append "console=ttyS0 quiet loglevel=3 panic=-1 systemd.show_status=0" \
  -virtfs local,path=/,mount_tag=hostroot,security_model=none,readonly=on,multidevs=remap \
  -virtfs local,path="$out",mount_tag=out,security_model=none,multidevs=remap \
  > "$job/console.txt" 2>&1
vm=$?
set -e
[ "$vm" = 124 ] && { tail -n 30 "$job/console.txt" >&2; echo "systemd_vm.sh: timed out after $timeout s" >&2; exit 124; }
cat "$out/output.txt" 2>/dev/null
[ -f "$out/.rc" ] || { tail -n 30 "$job/console.txt" >&2; echo "systemd_vm.sh: the command did not run (vm exit $vm)" >&2; exit 1; }
rc=$(cat "$out/.rc"); rm -f "$out/.rc"; exit "$rc"
