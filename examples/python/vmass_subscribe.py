#!/usr/bin/env python3
"""Subscribe to vmassd from Python: print each estimate and status as it arrives.

Needs the `vmass` types (installed with vmass: /usr/lib/python3/dist-packages/vmass from the
.deb) and LCM's Python bindings, which Debian 12 does not package: make a venv that also sees the
system's packages and install `lcm` from PyPI into it (docs/python.md):

    python3 -m venv --system-site-packages ~/vmass-venv
    ~/vmass-venv/bin/pip install lcm
    ~/vmass-venv/bin/python vmass_subscribe.py --count 100

Arrays decode to lists (status.input_valid[i] indexes, and a message re-encodes).
"""
import argparse
import sys
import time

import lcm

import vmass


def main():
    parser = argparse.ArgumentParser(description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--lcm-url", default="udpm://239.255.76.67:7667?ttl=0")
    parser.add_argument("--count", type=int, default=0, help="stop after this many estimates")
    parser.add_argument("--timeout", type=float, default=10.0, help="give up after this long, s")
    args = parser.parse_args()
    received = {"estimates": 0, "status": 0}

    def on_estimate(channel, data):
        e = vmass.mass_estimate_t.decode(data)
        received["estimates"] += 1
        if e.mass_known:
            print(f"{channel} t {e.utime * 1e-6:.2f} s  mass {e.mass_kg:.1f} kg  95% "
                  f"[{e.mass_ci_low_kg:.1f}, {e.mass_ci_high_kg:.1f}]  {e.status_name}")

    def on_status(channel, data):
        s = vmass.status_t.decode(data)
        received["status"] += 1
        invalid = [s.input_name[i] for i in range(s.num_inputs) if not s.input_valid[i]]
        print(f"{channel} vmassd {s.version} {s.state_name}  inputs valid "
              f"{s.num_inputs - len(invalid)} of {s.num_inputs}  invalid {invalid}")

    lc = lcm.LCM(args.lcm_url)
    lc.subscribe("VMASS_ESTIMATE", on_estimate)
    lc.subscribe("VMASS_STATUS", on_status)
    deadline = time.monotonic() + args.timeout
    while args.count <= 0 or received["estimates"] < args.count:
        if time.monotonic() > deadline:
            print(f"vmass_subscribe: {received} after {args.timeout} s", file=sys.stderr)
            return 1
        lc.handle_timeout(100)
    return 0


if __name__ == "__main__":
    sys.exit(main())
