#!/usr/bin/env python3
"""Times cantools decoding the frames of a candump -l log (the baseline of vmass-bench's decode/*).

Times are CPU time of this process (time.process_time_ns), as the C++ side measures CPU
time, so that other load on a shared machine does not skew the ratio.
Prints one JSON object: {"frames": N, "ns_per_frame_median": X, "runs": [...], "skipped": K}.
Frames are parsed from the log before timing; each run decodes every frame with
db.decode_message(frame_id, data, decode_choices=False), the usual cantools call (id lookup
included, as in vmass). Frames cantools cannot decode are left out (and counted).
"""
import argparse
import json
import statistics
import sys
import time

import cantools


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--dbc", required=True)
    ap.add_argument("--log", required=True)
    ap.add_argument("--runs", type=int, default=5)
    args = ap.parse_args()
    db = cantools.database.load_file(args.dbc, strict=False)
    frames, skipped = [], 0
    for line in open(args.log):
        parts = line.split()
        if len(parts) < 3 or "#" not in parts[2]:
            continue
        ident, data = parts[2].split("#", 1)
        if data.startswith("#"):
            data = data[2:]
        frame_id = int(ident, 16)
        payload = bytes.fromhex(data)
        try:
            db.decode_message(frame_id, payload, decode_choices=False)
        except Exception:
            skipped += 1
            continue
        frames.append((frame_id, payload))
    runs = []
    decode = db.decode_message
    for _ in range(args.runs):
        t0 = time.process_time_ns()
        for frame_id, payload in frames:
            decode(frame_id, payload, decode_choices=False)
        runs.append((time.process_time_ns() - t0) / len(frames))
    print(json.dumps({"frames": len(frames), "ns_per_frame_median": statistics.median(runs),
                      "runs": runs, "skipped": skipped, "cantools": cantools.__version__}))


if __name__ == "__main__":
    sys.exit(main())
