"""Writes one candump -l log again as Vector ASC, Vector BLF and PEAK TRC (python-can's writers)
and as ASAM MDF4 bus logging (asammdf), the independent writers vmass's readers are tested on.

    write_logs.py DRIVE.log OUT_DIR [--bad-mdf-record N]

OUT_DIR gets drive.asc, drive.blf, drive.trc and drive.mf4, each frame on the channel (bus) of
its interface: canN is channel (bus) N + 1. --bad-mdf-record N makes the MDF4
record N (1-based) a classic frame of 9 bytes, which the reader must report and skip. Run with
TZ=UTC: python-can writes ASC dates in local time, vmass reads them as UTC.
"""
import argparse
import datetime
import os

import can
import numpy as np
from asammdf import MDF, Signal
from asammdf.blocks import v4_constants as v4c
from asammdf.blocks.source_utils import Source


def write_with(writer_class, path, messages):
    writer = writer_class(path)
    for m in messages:
        writer.on_message_received(m)
    writer.stop()


def write_mdf4(path, messages, bad_record):
    """CAN_DataFrame bus logging as CANedge writes it: one structure channel per frame."""
    fields = [("CAN_DataFrame.BusChannel", "u1"), ("CAN_DataFrame.ID", "u4"),
              ("CAN_DataFrame.IDE", "u1"), ("CAN_DataFrame.DLC", "u1"),
              ("CAN_DataFrame.DataLength", "u1"), ("CAN_DataFrame.DataBytes", "u1", (64,)),
              ("CAN_DataFrame.Dir", "u1"), ("CAN_DataFrame.EDL", "u1"),
              ("CAN_DataFrame.BRS", "u1"), ("CAN_DataFrame.ESI", "u1")]
    samples = np.zeros(len(messages), dtype=np.dtype(fields))
    for k, m in enumerate(messages):
        row = samples[k]
        # MDF numbers buses from 1: interface canN is bus N + 1 (python-can's writers make it
        # channel N + 1 likewise)
        row["CAN_DataFrame.BusChannel"] = 1 + (can.util.channel2int(m.channel) or 0)
        row["CAN_DataFrame.ID"] = m.arbitration_id | (0x80000000 if m.is_extended_id else 0)
        row["CAN_DataFrame.IDE"] = int(m.is_extended_id)
        row["CAN_DataFrame.DLC"] = m.dlc
        row["CAN_DataFrame.DataLength"] = len(m.data)
        row["CAN_DataFrame.DataBytes"][: len(m.data)] = list(m.data)
        row["CAN_DataFrame.EDL"] = int(m.is_fd)
        row["CAN_DataFrame.BRS"] = int(m.bitrate_switch)
        row["CAN_DataFrame.ESI"] = int(m.error_state_indicator)
    if bad_record:
        samples[bad_record - 1]["CAN_DataFrame.DataLength"] = 9
        samples[bad_record - 1]["CAN_DataFrame.EDL"] = 0
    start = messages[0].timestamp
    times = np.array([m.timestamp - start for m in messages])
    bus = Source("CAN", "CAN", "CAN bus", v4c.SOURCE_BUS, v4c.BUS_TYPE_CAN)
    mdf = MDF(version="4.11")
    mdf.header.start_time = datetime.datetime.fromtimestamp(start, datetime.timezone.utc)
    mdf.append(Signal(samples, times, name="CAN_DataFrame", source=bus), acq_name="CAN",
               acq_source=bus)
    mdf.save(path, overwrite=True)


def main():
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("log")
    parser.add_argument("out_dir")
    parser.add_argument("--bad-mdf-record", type=int, default=0)
    args = parser.parse_args()
    messages = list(can.CanutilsLogReader(args.log))
    os.makedirs(args.out_dir, exist_ok=True)
    out = lambda name: os.path.join(args.out_dir, name)  # noqa: E731
    write_with(can.ASCWriter, out("drive.asc"), messages)
    write_with(can.BLFWriter, out("drive.blf"), messages)
    write_with(can.TRCWriter, out("drive.trc"), messages)
    write_mdf4(out("drive.mf4"), messages, args.bad_mdf_record)
    print(f"write_logs.py: {len(messages)} frames as ASC, BLF, TRC, MDF4 in {args.out_dir}")


if __name__ == "__main__":
    main()
