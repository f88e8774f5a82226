#!/bin/bash
# vcan_vm.sh: run one command where a real SocketCAN stack exists, on a host whose kernel has
# none (AF_CAN missing). vmass's own copy of the recipe, used by the vcan integration test.
#
#   vcan_vm.sh [--ifaces vcan0,vcan1] [--out DIR] [--timeout SECONDS] [--mem MB] -- COMMAND [ARG...]
#
# How: Debian's stock kernel boots under qemu (TCG software emulation, ~10-20 s). The host's root
# filesystem is shared read-only over virtio-9p, so binaries built here run unchanged inside. An
# initramfs (busybox) loads the CAN modules (can, can-raw, vcan), mounts the host root, creates
# the vcan interfaces, brings up loopback with a multicast route, and runs COMMAND as root in the
# current directory through chroot. Only $VCAN_VM_OUT (= $TMPDIR = $HOME inside) is writable: the
# --out folder (default: a temporary one, deleted afterwards), at the same path on both sides.
# COMMAND's output comes back on the terminal and its exit status becomes ours (124: timeout).
#
# The first run installs qemu-system-x86, busybox-static, cpio and kmod with apt-get (root) and
# unpacks the current linux-image package into ${VCAN_VM_CACHE:-~/.cache/vcan-vm}.
set -euo pipefail

ifaces=vcan0
timeout_s=120
mem_mb=1024
out_dir=
while [ $# -gt 0 ]; do
  case "$1" in
    --ifaces) ifaces=$2; shift 2 ;;
    --timeout) timeout_s=$2; shift 2 ;;
    --mem) mem_mb=$2; shift 2 ;;
    --out) out_dir=$2; shift 2 ;;
    --) shift; break ;;
    -h|--help) sed -n '2,19p' "$0"; exit 0 ;;
    *) echo "vcan_vm: unknown option $1" >&2; exit 2 ;;
  esac
done
[ $# -gt 0 ] || { echo "vcan_vm: no command (see --help)" >&2; exit 2; }

cache=${VCAN_VM_CACHE:-$HOME/.cache/vcan-vm}
mkdir -p "$cache"

# Host tools: install what is missing (Debian package names after the colon).
missing=()
for tool in qemu-system-x86_64:qemu-system-x86 busybox:busybox-static cpio:cpio depmod:kmod; do
  name=${tool%%:*}
  if ! command -v "$name" >/dev/null 2>&1 && [ ! -x "/sbin/$name" ]; then
    missing+=("${tool#*:}")
  fi
done
if [ ${#missing[@]} -gt 0 ]; then
  echo "vcan_vm: installing ${missing[*]}" >&2
  apt-get update -qq >/dev/null
  DEBIAN_FRONTEND=noninteractive apt-get install -y -qq "${missing[@]}" >/dev/null
fi
busybox_bin=$(command -v busybox || echo /bin/busybox)

# The kernel: the package linux-image-amd64 currently points to, unpacked once.
if [ ! -f "$cache/kernel.ok" ]; then
  echo "vcan_vm: fetching the Debian kernel package (first run only)" >&2
  apt-get update -qq >/dev/null || true
  kpkg=$(apt-cache depends linux-image-amd64 | awk '/Depends: linux-image-[0-9]/ {print $2; exit}')
  [ -n "$kpkg" ] || { echo "vcan_vm: cannot resolve linux-image-amd64" >&2; exit 1; }
  rm -rf "$cache/root" "$cache"/*.deb
  (cd "$cache" && apt-get download "$kpkg" >/dev/null 2>&1)
  dpkg-deb -x "$cache/${kpkg}"_*.deb "$cache/root"
  rm -f "$cache"/*.deb
  kver=$(ls "$cache/root/lib/modules")
  PATH=$PATH:/sbin depmod -b "$cache/root" "$kver"
  echo "$kver" > "$cache/kernel.ok"
fi
kver=$(cat "$cache/kernel.ok")

# A job folder holds the initramfs, the command and its exit status.
job=$(mktemp -d "${TMPDIR:-/tmp}/vmass-vcan-vm.XXXXXX")
trap 'rm -rf "$job"' EXIT
[ -n "$out_dir" ] || out_dir=$job/out
mkdir -p "$out_dir"
out_dir=$(cd "$out_dir" && pwd)
{
  printf 'cd %q || exit 97\n' "$PWD"
  printf 'export VCAN_VM_OUT=%q TMPDIR=%q HOME=%q PATH=%q\n' "$out_dir" "$out_dir" "$out_dir" "$PATH"
  printf '%q ' "$@"
  echo
} > "$job/cmd.sh"

# initramfs: busybox, the kernel modules needed (dependencies first), and /init.
rd=$job/initrd
mkdir -p "$rd"/{bin,proc,sys,dev,host,mods}
cp "$busybox_bin" "$rd/bin/busybox"
modules=()
for want in virtio_pci 9pnet_virtio 9p can-raw vcan; do
  while read -r _ path _; do
    base=$(basename "$path" .ko)
    case " ${modules[*]-} " in *" $base "*) continue ;; esac
    cp "$path" "$rd/mods/"
    modules+=("$base")
  done < <(PATH=$PATH:/sbin modprobe -d "$cache/root" -S "$kver" --show-depends "$want")
done
cat > "$rd/init" <<EOF
#!/bin/busybox sh
B=/bin/busybox
\$B mount -t proc proc /proc; \$B mount -t sysfs sys /sys; \$B mount -t devtmpfs dev /dev
for m in ${modules[*]}; do \$B insmod /mods/\$m.ko || echo "vcan_vm: insmod \$m failed"; done
\$B mount -t 9p -o trans=virtio,version=9p2000.L,ro hostroot /host || { echo "vcan_vm: cannot mount the host root"; \$B poweroff -f; }
\$B mount -t 9p -o trans=virtio,version=9p2000.L,rw job /host$job || { echo "vcan_vm: cannot mount the job folder"; \$B poweroff -f; }
\$B mount -t 9p -o trans=virtio,version=9p2000.L,rw out /host$out_dir || { echo "vcan_vm: cannot mount the out folder"; \$B poweroff -f; }
\$B mount -t proc proc /host/proc; \$B mount -t sysfs sys /host/sys; \$B mount -t devtmpfs dev /host/dev
\$B chroot /host /bin/sh -c '
  ip link set lo up; ip link set lo multicast on; ip route add 224.0.0.0/4 dev lo
  for i in $(echo "$ifaces" | tr , ' '); do ip link add dev \$i type vcan && ip link set \$i up; done
  sh $job/cmd.sh; echo \$? > $job/rc'
\$B sync; \$B poweroff -f
EOF
chmod +x "$rd/init"
(cd "$rd" && find . | cpio -o -H newc 2>/dev/null | gzip -1 > "$job/initrd.gz")

set +e
timeout "$timeout_s" qemu-system-x86_64 -accel tcg,thread=multi -cpu max -smp 2 -m "$mem_mb" \
  -nic none -nographic -no-reboot \
  -kernel "$cache/root/boot/vmlinuz-$kver" -initrd "$job/initrd.gz" \
  -append "console=ttyS0 quiet loglevel=3 panic=-1" \
  -virtfs local,path=/,mount_tag=hostroot,security_model=none,readonly=on,multidevs=remap \
  -virtfs local,path="$job",mount_tag=job,security_model=none,multidevs=remap \
  -virtfs local,path="$out_dir",mount_tag=out,security_model=none,multidevs=remap \
  2>&1 | sed -u -e 's/\x1b\[[0-9;?]*[a-zA-Z]//g' -e 's/\x1bc//g' -e 's/\r//g' \
    -e 's/SeaBIOS (version [^)]*)//; s/iPXE (http[^)]*).*PMM[^ ]*//; s/Press Ctrl-B to configure iPXE[^.]*\.\.\.//' \
    -e 's/Booting from ROM\.*//; s/^\[ *[0-9.]*\] reboot: Power down//' -e '/^\s*$/d'
vm_status=${PIPESTATUS[0]}
set -e
if [ "$vm_status" = 124 ]; then
  echo "vcan_vm: timed out after $timeout_s s" >&2
  exit 124
fi
[ -f "$job/rc" ] || { echo "vcan_vm: the command did not run (qemu exit $vm_status)" >&2; exit 1; }
exit "$(cat "$job/rc")"
