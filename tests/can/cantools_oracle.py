#!/usr/bin/env python3
"""Oracle test: vmass-can decode --json against cantools on random frames of real DBC files.

For every message of every DBC in the folder, random payloads (seeded) are written to a
candump -l log; the log is decoded by `vmass-can decode --json` and, frame by frame, by cantools
(decode_choices=False). Every signal present in either result must be present in both with the
same value to within float rounding. Multiplexed messages get valid switch values so that the
signals their multiplexor selects are compared (the selected set must match too).

Where cantools cannot load a file as it is, the comparison runs on what it can load, and says
so: cantools 45.1 refuses ids above 0x7FF without bit 31 (toyota_2017_ref_pt.dbc), so those
messages are removed from a temporary copy given to cantools (vmass still loads the original);
signals that lie beyond their message's payload (FORD_CADS_64.dbc) are refused by vmass and
loaded by cantools only with strict=False (it cannot decode the message then), so they are
removed from cantools' copy too. Every file is loaded with strict=False.

Exit status 0 when everything matches, 1 otherwise (and when cantools is missing).
"""
import argparse
import json
import math
import os
import random
import re
import subprocess
import sys
import tempfile

try:
    import cantools
except ImportError:
    print("cantools_oracle: the Python package cantools is missing in " + sys.executable +
          "; run scripts/install-python-deps.sh", file=sys.stderr)
    sys.exit(1)


def set_bits(data, start, length, little_endian, value):
    """Writes value into data (bytearray) at a DBC signal position (the ECOSYSTEM.md walk)."""
    if little_endian:
        for i in range(length):
            b = start + i
            bit = (value >> i) & 1
            data[b // 8] = (data[b // 8] & ~(1 << (b % 8))) | (bit << (b % 8))
    else:
        b = start
        for i in range(length):
            bit = (value >> (length - 1 - i)) & 1
            data[b // 8] = (data[b // 8] & ~(1 << (b % 8))) | (bit << (b % 8))
            b = b + 15 if b % 8 == 0 else b - 1


def fits(signal, length_bytes):
    if signal.byte_order == "little_endian":
        last = signal.start + signal.length - 1
    else:
        last = (signal.start // 8) * 8 + (7 - signal.start % 8) + signal.length - 1
    return last < 8 * length_bytes


def bits_of(signal):
    if signal.byte_order == "little_endian":
        return set(range(signal.start, signal.start + signal.length))
    first = (signal.start // 8) * 8 + (7 - signal.start % 8)  # big-endian linear position
    return {(p // 8) * 8 + (7 - p % 8) for p in range(first, first + signal.length)}


def can_coexist(a, b):
    if a.multiplexer_ids is None or b.multiplexer_ids is None:
        return True
    return a.multiplexer_signal != b.multiplexer_signal or bool(
        set(a.multiplexer_ids) & set(b.multiplexer_ids))


def remove_signals(text, message_name, names):
    lines, out, inside = text.split("\n"), [], False
    for line in lines:
        if re.match(r"^BO_ \d+ " + re.escape(message_name) + r"\s*:", line):
            inside = True
        elif not re.match(r"^\s+SG_ ", line):
            inside = False
        m = re.match(r"^\s+SG_ (\w+)", line)
        if inside and m and m.group(1) in names:
            continue
        out.append(line)
    return "\n".join(out)


def load_for_cantools(path, notes, not_compared):
    """cantools database for path, from a temporary copy without the messages it refuses."""
    text = open(path, encoding="utf-8", errors="surrogateescape").read()
    dropped = []

    def drop_block(txt, name):
        lines = txt.split("\n")
        out, skipping = [], False
        for line in lines:
            if re.match(r"^BO_ \d+ " + re.escape(name) + r"\s*:", line):
                skipping = True
                continue
            if skipping and re.match(r"^\s+SG_ ", line):
                continue
            skipping = False
            out.append(line)
        return "\n".join(out)

    # Known refusal: ids above 0x7FF without bit 31.
    for m in re.finditer(r"^BO_ (\d+) (\w+)\s*:", text, re.M):
        frame_id, name = int(m.group(1)), m.group(2)
        if 0x7FF < frame_id < 0x80000000 and name != "VECTOR__INDEPENDENT_SIG_MSG":
            dropped.append(name)
    for name in dropped:
        text = drop_block(text, name)
    for _ in range(100):
        try:
            db = cantools.database.load_string(text, database_format="dbc", strict=False)
            break
        except Exception as e:  # anything else it refuses: drop the message it names
            m = re.search(r"message '?(\w+)'?", str(e))
            if not m or m.group(1) in dropped:
                raise
            dropped.append(m.group(1))
            text = drop_block(text, m.group(1))
    # Signals beyond their payload: cantools loads them only with strict=False and then cannot
    # decode the message; vmass refuses them. Overlapping signals (both present at once): cantools
    # cannot decode the message; vmass decodes both and warns. Take them out of cantools' copy.
    beyond, overlapping = [], []
    for msg in db.messages:
        bad = [sig.name for sig in msg.signals if not fits(sig, msg.length)]
        seen = []
        for sig in msg.signals:
            if sig.name in bad:
                continue
            if any(can_coexist(sig, o) and bits_of(sig) & bits_of(o) for o in seen):
                overlapping.append("%s.%s" % (msg.name, sig.name))
                bad.append(sig.name)
                not_compared.setdefault(msg.name, set()).add(sig.name)
                continue
            seen.append(sig)
        if bad:
            text = remove_signals(text, msg.name, set(bad))
        beyond += ["%s.%s" % (msg.name, b) for b in bad if "%s.%s" % (msg.name, b) not in
                   overlapping]
    if beyond or overlapping:
        db = cantools.database.load_string(text, database_format="dbc", strict=False)
    if beyond:
        notes.append("%s: %d signal(s) lie beyond their message's payload: refused by vmass, "
                     "loaded by cantools only with strict=False (and then undecodable); not "
                     "compared: %s" % (os.path.basename(path), len(beyond), ", ".join(beyond)))
    if overlapping:
        notes.append("%s: %d signal(s) overlap another signal of their message: cantools cannot "
                     "decode such a message, so they are taken out of its copy and not compared: "
                     "%s" % (os.path.basename(path), len(overlapping), ", ".join(overlapping)))
    if dropped:
        notes.append("%s: cantools refuses %d message(s) (ids above 0x7FF without bit 31 or "
                     "otherwise); compared without them: %s" %
                     (os.path.basename(path), len(dropped), ", ".join(dropped[:6]) +
                      (" ..." if len(dropped) > 6 else "")))
    return db


def close(a, b):
    if a is None or b is None:  # JSON null: NaN or infinity
        x = b if a is None else a
        return (a is None and b is None) or (isinstance(x, float) and not math.isfinite(x))
    if isinstance(a, float) and math.isnan(a):
        return isinstance(b, float) and math.isnan(b)
    return abs(a - b) <= 1e-12 * max(1.0, abs(a), abs(b))


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--vmass-can", required=True)
    ap.add_argument("--dbc-dir", required=True)
    ap.add_argument("--frames", type=int, default=20, help="frames per message")
    ap.add_argument("--seed", type=int, default=20240601)
    args = ap.parse_args()

    rng = random.Random(args.seed)
    notes, failures = [], []
    total_frames = total_signals = 0
    files = sorted(f for f in os.listdir(args.dbc_dir) if f.endswith(".dbc"))
    if not files:
        print("cantools_oracle: no DBC files in " + args.dbc_dir, file=sys.stderr)
        return 1
    for name in files:
        path = os.path.join(args.dbc_dir, name)
        not_compared = {}
        db = load_for_cantools(path, notes, not_compared)
        frames = []  # (message, payload)
        for msg in db.messages:
            if msg.name == "VECTOR__INDEPENDENT_SIG_MSG":
                continue
            switches = {s.name: s for s in msg.signals if s.is_multiplexer}
            switch_values = {}
            for s in msg.signals:
                if s.multiplexer_signal:
                    switch_values.setdefault(s.multiplexer_signal, set()).update(
                        s.multiplexer_ids or [])
            for _ in range(args.frames):
                data = bytearray(rng.getrandbits(8) for _ in range(msg.length))
                for sw_name, values in switch_values.items():
                    sw = switches[sw_name]
                    set_bits(data, sw.start, sw.length, sw.byte_order == "little_endian",
                             rng.choice(sorted(values)))
                frames.append((msg, bytes(data)))
        with tempfile.NamedTemporaryFile("w", suffix=".log", delete=False) as log:
            for i, (msg, data) in enumerate(frames):
                ext = msg.is_extended_frame
                ident = ("%08X" if ext else "%03X") % msg.frame_id
                fd = msg.is_fd or msg.length > 8
                log.write("(%010d.%06d) can0 %s#%s%s\n" % (1700000000 + i // 1000000,
                                                            i % 1000000, ident,
                                                            "#0" if fd else "",
                                                            data.hex().upper()))
            log_path = log.name
        try:
            out = subprocess.run([args.vmass_can, "decode", "--dbc", path, "--json", log_path],
                                 capture_output=True, text=True, check=False)
        finally:
            os.unlink(log_path)
        # A DBC with errors (FORD's signals beyond their payload) is decoded with what loaded,
        # and decode exits 2 for it; any other failure is one.
        partial = out.returncode == 2 and "decoding with what could be loaded" in out.stderr
        if out.returncode != 0 and not partial:
            failures.append("%s: vmass-can decode exited %d: %s" % (name, out.returncode,
                                                                   out.stderr[-500:]))
            continue
        decoded = [json.loads(line) for line in out.stdout.splitlines() if line.strip()]
        if len(decoded) != len(frames):
            failures.append("%s: vmass decoded %d of %d frames" % (name, len(decoded),
                                                                  len(frames)))
            continue
        for (msg, data), ours in zip(frames, decoded):
            total_frames += 1
            if ours["id"] != msg.frame_id or ours["message"] != msg.name:
                failures.append("%s: frame of %s decoded as %s" % (name, msg.name,
                                                                   ours["message"]))
                continue
            theirs = msg.decode(data, decode_choices=False)
            mine = {k: v for k, v in ours["signals"].items()
                    if k not in not_compared.get(msg.name, ())}
            if set(mine) != set(theirs):
                failures.append("%s %s payload %s: signal sets differ: only vmass %s, only "
                                "cantools %s" % (name, msg.name, data.hex(),
                                                 sorted(set(mine) - set(theirs)),
                                                 sorted(set(theirs) - set(mine))))
                continue
            for sig_name, value in theirs.items():
                total_signals += 1
                if not close(mine[sig_name], float(value)):
                    failures.append("%s %s.%s payload %s: vmass %r cantools %r" %
                                    (name, msg.name, sig_name, data.hex(), mine[sig_name],
                                     value))
        print("cantools_oracle: %s: %d frames compared" % (name, len(frames)))
    for n in notes:
        print("note: " + n)
    for f in failures[:50]:
        print("MISMATCH: " + f)
    print("cantools_oracle: %d frames, %d signal values compared, %d mismatches" %
          (total_frames, total_signals, len(failures)))
    return 1 if failures or total_signals == 0 else 0


if __name__ == "__main__":
    sys.exit(main())
