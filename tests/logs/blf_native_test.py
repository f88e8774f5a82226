"""Vector BLF read natively against python-can (its BLFReader is the reference of the layout):
the frames vmass reads are exactly those python-can reads, each as vmass-log-convert made it,
on BLF files written by python-can's BLFWriter (classic, extended, remote, CAN FD, error
frames, several channels; zlib at two levels and stored; containers small enough that objects
go on in the next) and on files laid out by hand with what python-can reads but does not write
(header version 2, 10 us time stamps, CAN_MESSAGE2, CAN_FD_MESSAGE_64 with extension data,
APP_TEXT and GLOBAL_MARKER objects, padding).

Cut at many offsets, each file gives exactly the frames python-can reads of the cut file and
one located "truncated" record; damaged (bytes flipped, sizes made huge or small, zlib data
overwritten), it never crashes, gives the frames python-can reads of the file up to the
damaged container, never a frame that is not in the file from a zlib container, and every
report names its record and place.

    blf_native_test.py BIN_DIR OUT_DIR
"""
import os
import random
import struct
import subprocess
import sys
import zlib

try:
    import can
except ImportError:
    print("skip: this Python lacks python-can (scripts/install-python-deps.sh)")
    sys.exit(77)  # ctest's SKIP_RETURN_CODE

BIN, OUT = sys.argv[1], sys.argv[2]
FD_LENGTHS = (0, 1, 2, 3, 4, 5, 6, 7, 8, 12, 16, 20, 24, 32, 48, 64)
failures = []


def fail(message):
    failures.append(message)
    print("FAIL: " + message)


# ---- what python-can reads, as the vmass tools print it (vmass-can decode echoes candump -l)

def oracle(path):
    """python-can's frames of the file (up to where it stops reading), each as the candump -l
    line of the frame vmass-log-convert made of it, and how many it could not take."""
    lines, refused = [], 0
    try:
        for m in can.BLFReader(path):
            line = candump_line(m)
            if line is None:
                refused += 1
            else:
                lines.append(line)
    except Exception:  # noqa: BLE001: python-can stops at damage; its frames so far count
        pass
    return lines, refused


def candump_line(m):
    t_us = round(m.timestamp * 1e6)
    channel = m.channel if isinstance(m.channel, int) and m.channel >= 0 else 0
    head = f"({t_us // 1000000:010d}.{t_us % 1000000:06d}) can{channel} "
    data = bytes(m.data)
    if m.is_error_frame:
        return head + f"{0x20000000 | (m.arbitration_id & 0x1FFFFFFF):08X}#" + data[:8].hex().upper()
    if m.arbitration_id > (0x1FFFFFFF if m.is_extended_id else 0x7FF):
        return None
    if (m.is_fd and len(data) not in FD_LENGTHS) or (not m.is_fd and len(data) > 8):
        return None
    ident = f"{m.arbitration_id:08X}" if m.is_extended_id else f"{m.arbitration_id:03X}"
    if m.is_remote_frame:  # a remote request keeps its DLC
        n = min(m.dlc, 8)
        return head + ident + "#R" + (str(n) if n else "")
    if m.is_fd:
        flags = (1 if m.bitrate_switch else 0) | (2 if m.error_state_indicator else 0)
        return head + ident + f"##{flags:X}" + data.hex().upper()
    return head + ident + "#" + data.hex().upper()


EMPTY_DBC = os.path.join(OUT, "empty.dbc")


def native(path):
    """vmass's frames of the file (vmass-can decode with a DBC without messages echoes each as
    candump -l), its records' reports, its summary line and exit code."""
    # No converter, no Python: BLF is read natively.
    env = dict(os.environ, VMASS_LOG_CONVERT="/nonexistent/vmass-log-convert",
               VMASS_PYTHON="/nonexistent/python")
    p = subprocess.run([os.path.join(BIN, "vmass-can"), "decode", "--dbc", EMPTY_DBC, path],
                       capture_output=True, text=True, timeout=120, env=env)
    err = [l for l in p.stderr.splitlines() if "no message (BO_)" not in l]
    reports = [l for l in err if l.startswith(path + ":record ")]
    summary = [l for l in err if l.startswith("vmass-can decode: Vector BLF")]
    return p.stdout.splitlines(), reports, (summary[0] if summary else ""), p.returncode, err


# ---- files written by python-can

def messages(seed, count):
    rnd = random.Random(seed)
    t = 1700000000.0 + rnd.random()
    out = []
    for _ in range(count):
        t += rnd.choice((0.0, 1e-6, 1.5e-5, 0.000123457, 0.01, rnd.random() * 0.002))
        channel = rnd.choice((None, 0, 1, 2, 7))
        kind = rnd.random()
        extended = rnd.random() < 0.3
        ident = rnd.getrandbits(29 if extended else 11)
        if kind < 0.55:
            data = bytes(rnd.getrandbits(8) for _ in range(rnd.randint(0, 8)))
            m = can.Message(timestamp=t, arbitration_id=ident, is_extended_id=extended, data=data,
                            channel=channel)
        elif kind < 0.65:
            m = can.Message(timestamp=t, arbitration_id=ident, is_extended_id=extended,
                            is_remote_frame=True, dlc=rnd.randint(0, 8), channel=channel)
        elif kind < 0.95:
            n = rnd.choice(FD_LENGTHS)
            m = can.Message(timestamp=t, arbitration_id=ident, is_extended_id=extended, is_fd=True,
                            bitrate_switch=rnd.random() < 0.5,
                            error_state_indicator=rnd.random() < 0.2,
                            data=bytes(rnd.getrandbits(8) for _ in range(n)), channel=channel)
        else:
            m = can.Message(timestamp=t, arbitration_id=rnd.getrandbits(8), is_error_frame=True,
                            data=bytes(rnd.getrandbits(8) for _ in range(rnd.randint(0, 8))),
                            channel=channel)
        out.append(m)
    return out


def write_python_can(path, msgs, **kwargs):
    w = can.BLFWriter(path, **kwargs)
    for m in msgs:
        w.on_message_received(m)
    w.stop()


# ---- files laid out by hand (python-can reads these objects; its writer does not write them)

def obj(obj_type, fields, stamp, flags=2, version=1):
    header = 40 if version == 2 else 32
    size = header + len(fields)
    o = struct.pack("<4sHHLL", b"LOBJ", header, version, size, obj_type)
    if version == 2:
        o += struct.pack("<LBxHQ8x", flags, 0, 0, stamp)
    else:
        o += struct.pack("<LHHQ", flags, 0, 0, stamp)
    return o + fields + b"\0" * (size % 4)


def container(data, compress):
    payload = zlib.compress(data) if compress else data
    size = 32 + len(payload)
    return (struct.pack("<4sHHLL", b"LOBJ", 16, 1, size, 10) +
            struct.pack("<H6xL4x", 2 if compress else 0, len(data)) + payload + b"\0" * (size % 4))


def by_hand(path, chunk, compress):
    inner = b""
    rnd = random.Random(7)
    for i in range(400):
        stamp = i * 123457
        k = i % 8
        if k == 0:  # CAN_MESSAGE2, header version 2
            f = struct.pack("<HBBL8s", 1 + i % 3, 0, 8, 0x100 + i, bytes(range(i % 200, i % 200 + 8)))
            inner += obj(86, f + struct.pack("<LBBH", 1000, 100, 0, 0), stamp, 2, 2)
        elif k == 1:  # 10 us time stamps
            f = struct.pack("<HBBL8s", 2, 0x80 if i % 16 == 1 else 0, 5, 0x80000000 | (0x1000 + i),
                            b"abcdefgh")
            inner += obj(1, f, stamp // 10000, 1)
        elif k == 2:  # CAN_FD_MESSAGE_64, data up to its end
            n = FD_LENGTHS[i % 16]
            f = struct.pack("<BBBBLLLLLLLHBBL", 1, i % 16, n, 0, 0x200 + i, 0, 0x1000 | 0x2000, 0,
                            0, 0, 0, 0, 0, 0, 0) + bytes(rnd.getrandbits(8) for _ in range(n))
            inner += obj(101, f, stamp)
        elif k == 3:  # CAN_FD_MESSAGE_64 with extension data: the data field ends there
            f = struct.pack("<BBBBLLLLLLLHBBL", 2, 10, 16, 0, 0x300 + i, 0, 0x1000 | 0x4000, 0, 0,
                            0, 0, 0, 0, 32 + 40 + 6, 0) + bytes(range(16)) + b"EXTENSION"
            inner += obj(101, f, stamp)
        elif k == 4:  # APP_TEXT
            text = b"comment %d" % i
            inner += obj(65, struct.pack("<LLL", 0, len(text), 0) + text, stamp)
        elif k == 5:  # GLOBAL_MARKER
            inner += obj(96, bytes(60 + i % 7), stamp)
        elif k == 6:  # CAN_ERROR_EXT
            f = struct.pack("<HHLBBBxLLH2x8s", 3, 0, 0, 0, 0, 4, 0, 0x123, 0, b"\1\2\3\4\0\0\0\0")
            inner += obj(73, f, stamp)
        else:  # CAN_FD_MESSAGE, a classic frame in it (no EDL), channel 0
            f = struct.pack("<HBBLLBBB5x64s", 0, 0, 6, 0x7F0, 0, 0, 0, 6, b"sixsix")
            inner += obj(100, f, stamp)
    body = b"".join(container(inner[a:a + chunk], compress) for a in range(0, len(inner), chunk))
    start = (2022, 11, 2, 15, 13, 45, 30, 250)
    header = struct.pack("<4sLBBBBBBBBQQLL8H8H", b"LOGG", 144, 5, 0, 0, 0, 2, 6, 8, 1,
                         144 + len(body), 144 + len(inner), 400, 0, *start, *start)
    with open(path, "wb") as f:
        f.write(header + b"\0" * (144 - len(header)) + body)


def containers_of(data):
    """(begin, end) of each top-level object of an undamaged file."""
    out, at = [], struct.unpack_from("<L", data, 4)[0]
    while at + 16 <= len(data):
        size = struct.unpack_from("<L", data, at + 8)[0]
        out.append((at, at + size + size % 4))
        at += size + size % 4
    return out


def main():
    os.makedirs(OUT, exist_ok=True)
    with open(EMPTY_DBC, "w") as f:
        f.write('VERSION ""\n')
    msgs = messages(1, 3000)
    files = {
        "default.blf": dict(),
        "spanning.blf": dict(max_container_size=300),
        "stored.blf": dict(compression_level=0, max_container_size=1000),
        "level9.blf": dict(compression_level=9),
    }
    paths = []
    for name, kwargs in files.items():
        path = os.path.join(OUT, name)
        write_python_can(path, msgs, **kwargs)
        paths.append(path)
    early = os.path.join(OUT, "before_1990.blf")  # no start time: the offsets alone
    write_python_can(early, [can.Message(timestamp=1000.0 + 0.25 * i, arbitration_id=i, data=b"x")
                             for i in range(50)])
    empty = os.path.join(OUT, "empty.blf")
    write_python_can(empty, [])
    paths += [early, empty]
    for name, chunk, compress in (("by_hand.blf", 131072, True), ("by_hand_spanning.blf", 97, True),
                                  ("by_hand_stored.blf", 250, False)):
        by_hand(os.path.join(OUT, name), chunk, compress)
        paths.append(os.path.join(OUT, name))

    # Whole files: exactly python-can's frames, nothing reported.
    for path in paths:
        expected, refused = oracle(path)
        got, reports, summary, rc, _ = native(path)
        if got != expected:
            diff = next((i for i, (a, b) in enumerate(zip(got, expected)) if a != b),
                        min(len(got), len(expected)))
            fail(f"{path}: {len(got)} frames natively, python-can {len(expected)}; first "
                 f"difference at {diff}: {got[diff:diff + 1]} vs {expected[diff:diff + 1]}")
        elif reports or refused or rc != 0:
            fail(f"{path}: reports {reports[:3]}, python-can refused {refused}, exit {rc}")
        else:
            print(f"ok: {os.path.basename(path)}: {len(got)} frames natively, python-can "
                  f"{len(expected)}, identical ({summary.split(', ', 1)[-1]})")

    # Cut files: python-can's frames of the cut file, one located "truncated" record.
    for path in (paths[1], paths[2], paths[6], paths[8]):
        data = open(path, "rb").read()
        cuts = set(range(4, len(data), max(1, len(data) // 150)))  # "LOGG" tells BLF
        for begin, end in containers_of(data)[:12]:
            cuts.update(c for c in (begin - 1, begin, begin + 1, begin + 15, begin + 16,
                                    begin + 31, begin + 32, begin + 33, end - 5, end - 1)
                        if 4 <= c < len(data))
        cut_path = path + ".cut"
        bad = 0
        for cut in sorted(cuts):
            with open(cut_path, "wb") as f:
                f.write(data[:cut])
            expected, _ = oracle(cut_path)
            got, reports, _, rc, err = native(cut_path)
            truncated = [r for r in reports if ": truncated: " in r]
            if got != expected or len(truncated) != 1 or rc not in (0, 2):
                bad += 1
                if bad <= 3:
                    fail(f"{path} cut at {cut}: {len(got)} frames natively, python-can "
                         f"{len(expected)}, exit {rc}, reports {reports[:3]} {err[-1:]}")
        if not bad:
            print(f"ok: {os.path.basename(path)} cut at {len(cuts)} offsets: python-can's frames "
                  f"before each cut, one located 'truncated' record (e.g. {truncated[0]})")

    # Damaged files: no crash, python-can's frames up to the damaged container, no frame from
    # a zlib container that is not in the file, every report located.
    rnd = random.Random(3)
    shown = 0
    for path in (paths[1], paths[0], paths[2], paths[7]):
        data = open(path, "rb").read()
        whole, _ = oracle(path)
        objects = containers_of(data)
        zlib_file = "stored" not in path
        damages = []
        for _ in range(120):
            at = rnd.randrange(144, len(data))
            damages.append(("flip", at, bytes([data[at] ^ (1 << rnd.randrange(8))])))
        for begin, _ in objects[1:40:3]:
            damages.append(("huge size", begin + 8, struct.pack("<L", 0xFFFFFFF0)))
            damages.append(("small size", begin + 8, struct.pack("<L", 20)))
            damages.append(("zlib data", begin + 40, b"\xde\xad\xbe\xef" * 4))
            damages.append(("signature", begin, b"LOBX"))
        bad = 0
        for kind, at, patch in damages:
            damaged = data[:at] + patch + data[at + len(patch):]
            damaged_path = path + ".damaged"
            with open(damaged_path, "wb") as f:
                f.write(damaged)
            container_begin = max(b for b, _ in objects if b <= at)
            with open(damaged_path + ".before", "wb") as f:
                f.write(data[:container_begin])
            before, _ = oracle(damaged_path + ".before")
            got, reports, _, rc, err = native(damaged_path)
            problems = []
            if rc not in (0, 2):
                problems.append(f"exit {rc}: {err[-3:]}")
            if got[:len(before)] != before:
                problems.append(f"the {len(before)} frames before the damage differ")
            if any("file offset " not in r and "the file has" not in r for r in reports):
                problems.append(f"a report without its place: {reports}")
            if zlib_file:
                k = 0
                for line in got:
                    while k < len(whole) and whole[k] != line:
                        k += 1
                    if k == len(whole):
                        problems.append(f"a frame not in the file: {line}")
                        break
                    k += 1
            if problems:
                bad += 1
                if bad <= 3:
                    fail(f"{path}, {kind} at {at}: {'; '.join(problems)}")
            elif reports and shown < 6 and kind != "flip" or (reports and shown < 2):
                shown += 1
                print(f"   {kind} at byte {at} of {os.path.basename(path)}: {len(got)} of "
                      f"{len(whole)} frames; {reports[0].split('/')[-1]}")
        if not bad:
            print(f"ok: {os.path.basename(path)}: {len(damages)} damaged copies read without a "
                  f"crash, the frames before each damage python-can's, every report located")

    if failures:
        print(f"blf_native_test: {len(failures)} failures")
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
