#!/usr/bin/env python3
"""The bad-input corpus: files from many hands, each case with the exit code and the exact
error (a substring of stderr, naming the file, line or key) it must produce.

    bad_inputs_test.py BIN_DIR SOURCE_DIR [--record]

--record prints what each case produced instead of checking (to write a new case's expectation;
read every message before you freeze it: it must say what is wrong and where)."""
import os
import subprocess
import sys
import tempfile

BIN, SRC = sys.argv[1], sys.argv[2]
RECORD = "--record" in sys.argv
GOLDEN = os.path.join(SRC, "tests/data/golden/paper_exp2")

GOOD_DBC = """VERSION ""
BU_: ECU
BO_ 256 Speed: 8 ECU
 SG_ VehicleSpeed : 0|16@1+ (0.01,0) [0|655.35] "km/h" ECU
 SG_ Counter : 56|4@1+ (1,0) [0|15] "" ECU
"""
BAD_DBC = {
    "empty": "",
    "garbage_binary": bytes(range(256)) * 64,
    "bo_without_id": 'VERSION ""\nBO_ Speed: 8 ECU\n',
    "sg_bad_start_bit": GOOD_DBC.replace("0|16@1+", "x|16@1+"),
    "sg_beyond_length": GOOD_DBC.replace("0|16@1+", "60|16@1+"),
    "sg_zero_factor": GOOD_DBC.replace("(0.01,0)", "(0,0)"),
    "sg_min_above_max": GOOD_DBC.replace("[0|655.35]", "[700|600]"),
    "duplicate_message_name": GOOD_DBC + "BO_ 257 Speed: 8 ECU\n SG_ X : 0|8@1+ (1,0) [0|255] \"\" ECU\n",
    "mux_value_too_wide": GOOD_DBC + "BO_ 300 Muxed: 8 ECU\n SG_ Page M : 0|2@1+ (1,0) [0|3] \"\" ECU\n SG_ Value m99999999999999999999 : 8|8@1+ (1,0) [0|255] \"\" ECU\n",
    "unterminated_quote": GOOD_DBC.replace('"km/h"', '"km/h'),
    "huge_name": GOOD_DBC.replace("VehicleSpeed", "S" * 50000),
    "sg_before_bo": 'VERSION ""\n SG_ X : 0|8@1+ (1,0) [0|255] "" ECU\n',
    "bad_byte_order": GOOD_DBC.replace("0|16@1+", "0|16@7+"),
    "zero_length_signal": GOOD_DBC.replace("0|16@1+", "0|0@1+"),
    "negative_dlc": GOOD_DBC.replace("Speed: 8", "Speed: -1"),
    "lowercase_switch": GOOD_DBC + "BO_ 300 Muxed: 8 ECU\n SG_ Page m : 0|2@1+ (1,0) [0|3] \"\" ECU\n SG_ Value m2 : 8|8@1+ (1,0) [0|255] \"\" ECU\n",
    "many_multiplexed": GOOD_DBC + "BO_ 300 Big: 8 ECU\n SG_ Page M : 0|16@1+ (1,0) [0|65535] \"\" ECU\n"
    + "".join(f" SG_ S{i} m{i} : 16|16@1+ (1,0) [0|0] \"\" ECU\n" for i in range(5000)),
    "two_errors": 'VERSION ""\nBO_ Speed: 8 ECU\nBO_ 300 X: 8 ECU\n SG_ Y : z|8@1+ (1,0) [0|255] "" ECU\n',
}

BASE_CONFIG = open(os.path.join(GOLDEN, "config.yaml")).read()


def config_with(old, new):
    assert old in BASE_CONFIG, old
    return BASE_CONFIG.replace(old, new, 1)


BAD_CONFIG = {
    "empty": "",
    "yaml_syntax": "vehicle:\n  empty_mass_kg: [1500\n",
    "missing_empty_mass": "\n".join(l for l in BASE_CONFIG.split("\n") if "empty_mass_kg" not in l),
    "unknown_key": config_with("vehicle:\n", "vehicle:\n  empty_mas_kg: 1500\n"),
    "duplicate_key": config_with("vehicle:\n", "vehicle:\n  wheelbase_m: 2.7\n  wheelbase_m: 2.8\n")
    if "wheelbase_m" not in BASE_CONFIG else config_with("  wheelbase_m:", "  wheelbase_m: 2.7\n  wheelbase_m:"),
    "string_for_number": config_with("  type: bayes", "  type: bayes\n  tick_rate_hz: fast"),
    "absurd_mass": config_with("vehicle:\n", "vehicle:\n  max_mass_kg: 1e300\n"),
    "negative_wheelbase": config_with("  wheelbase_m: 2.7", "  wheelbase_m: -2.7"),
    "cg_beyond_wheelbase": config_with("  wheelbase_m: 2.7", "  wheelbase_m: 1.0"),
    "mass_as_text": config_with("  empty_mass_kg: 1500", "  empty_mass_kg: heavy"),
    "nan_mass": config_with("  empty_mass_kg: 1500", "  empty_mass_kg: .nan"),
    "unknown_estimator": config_with("  type: bayes", "  type: kalman"),
    "credible_level_above_one": config_with("  type: bayes", "  type: bayes\n  bayes:\n    credible_level: 1.5"),
    "dt_below_tick": config_with("  type: bayes", "  type: bayes\n  differencing_dt_s: 0.001"),
    "huber_negative": config_with("  type: bayes", "  type: bayes\n  supervisor:\n    huber_k: -1"),
    "unknown_section": BASE_CONFIG + "\nbogus:\n  x: 1\n",
    "list_for_map": config_with("  type: bayes", "  type: bayes\n  longitudinal: [1, 2]"),
    "gear_ratios_not_list": config_with("vehicle:\n", "vehicle:\n  gear_ratios: 3.5\n"),
    "negative_gear_ratio": config_with("vehicle:\n", "vehicle:\n  gear_ratios: [3.5, -2.0]\n  final_drive_ratio: 4.0\n"),
    "levelled_not_bool": config_with("suspension:\n", "suspension:\n  levelled: maybe\n"),
    "load_change_zero_pairs": config_with("  type: bayes", "  type: bayes\n  load_change:\n    min_pairs: 0"),
    "huge_timeout": config_with("  type: bayes", "  type: bayes\n  lateral:\n    min_speed_mps: 1e13"),
    "null_value": config_with("  type: bayes", "  type: bayes\n  tick_rate_hz: ~"),
    "second_document": BASE_CONFIG + "\n---\nvehicle:\n  empty_mass_kg: 9\n",
    "nested_aliases": BASE_CONFIG + "\nx0: &l0 [lol]\n" + "".join(
        f"x{i}: &l{i} [{', '.join([f'*l{i - 1}'] * 10)}]\n" for i in range(1, 10)),
}

SAMPLES_HEADER = open(os.path.join(GOLDEN, "samples.csv")).readline()
BAD_SAMPLES = {
    "empty": "",
    "no_time_column": SAMPLES_HEADER.replace("time_s", "t"),
    "header_only": SAMPLES_HEADER,
    "binary": bytes(range(256)) * 16,
    "nan_time": SAMPLES_HEADER + "nan" + "," * SAMPLES_HEADER.count(",") + "\n",
}

BAD_BALLAST = {
    "empty": "",
    "no_columns": "a,b\n1,2\n",
    "one_mass": "time_s,added_mass_kg,rear_right_deflection_m\n0,0,0.01\n1,0,0.01\n",
    "not_a_number": "time_s,added_mass_kg,rear_right_deflection_m\n0,abc,0.01\n",
    "binary": bytes(range(256)) * 16,
}


def cases(tmp):
    """(name, argv[, standard output's path]) for every case; the table has its exit code and
    expected stderr substring."""
    out = []

    def write(name, content):
        path = os.path.join(tmp, name)
        with open(path, "wb") as f:
            f.write(content if isinstance(content, bytes) else content.encode())
        return path

    can = os.path.join(BIN, "vmass-can")
    replay = os.path.join(BIN, "vmass-replay")
    calibrate = os.path.join(BIN, "vmass-calibrate")
    vmassd = os.path.join(BIN, "vmassd")
    samples = os.path.join(GOLDEN, "samples.csv")
    config = os.path.join(GOLDEN, "config.yaml")
    for name, text in BAD_DBC.items():
        out.append(("dbc." + name, [can, "check", "--dbc", write(name + ".dbc", text)]))
    for name in ("sg_zero_factor", "lowercase_switch", "sg_min_above_max"):
        out.append(("dbc.strict." + name,
                    [can, "check", "--strict", "--dbc", os.path.join(tmp, name + ".dbc")]))
    out.append(("dbc.directory", [can, "check", "--dbc", tmp]))
    out.append(("dbc.dev_zero", [can, "check", "--dbc", "/dev/zero"]))
    out.append(("dbc.missing", [can, "check", "--dbc", os.path.join(tmp, "none.dbc")]))
    for name, text in BAD_CONFIG.items():
        out.append(("config." + name,
                    [replay, "--config", write(name + ".yaml", text), "--samples", samples]))
    out.append(("config.directory", [replay, "--config", tmp, "--samples", samples]))
    out.append(("config.dev_zero", [replay, "--config", "/dev/zero", "--samples", samples]))
    for name, text in BAD_SAMPLES.items():
        out.append(("samples." + name,
                    [replay, "--config", config, "--samples", write(name + ".csv", text)]))
    out.append(("samples.directory", [replay, "--config", config, "--samples", tmp]))
    for name, text in BAD_BALLAST.items():
        out.append(("ballast." + name, [calibrate, "--config", config, "--ballast",
                                        write("b_" + name + ".csv", text)]))
    out.append(("truth.empty", [replay, "--config", config, "--samples", samples, "--truth",
                                write("truth_empty.csv", "")]))
    out.append(("truth.other_time_base", [replay, "--config", config, "--samples", samples,
                                          "--truth", write("truth_late.csv",
                                                           "time_s,mass_kg\n5000,1500\n6000,1500\n")]))
    # An empty deflection written as a ride height: the static mass is -1363 kg; no mass at all
    # is published, and the warning says why (exit 0: the run itself went through).
    out.append(("replay.ride_height_as_empty_deflection", [replay, "--config", write(
        "ride_height.yaml", config_with("  empty_deflection_m: 0.0108872444444",
                                        "  empty_deflection_m: 0.35")), "--samples", samples]))
    out.append(("vmassd.speed_tiny", [vmassd, "--config", config, "--samples", samples,
                                      "--speed", "1e-300"]))
    out.append(("vmassd.speed_text", [vmassd, "--config", config, "--samples", samples,
                                      "--speed", "fast"]))
    out.append(("replay.log_and_samples", [replay, "--config", config, "--samples", samples,
                                           "--log", samples]))
    out.append(("vmassd.missing_config", [vmassd, "--config", os.path.join(tmp, "none.yaml")]))
    out.append(("vmassd.config_directory", [vmassd, "--config", tmp]))
    out.append(("can.decode_bad_dbc", [can, "decode", "--dbc", os.path.join(tmp, "empty.dbc"),
                                       samples]))
    out.append(("replay.unknown_estimator", [replay, "--config", config, "--samples", samples,
                                             "--estimator", "kalman"]))
    # Logs, through the CAN-log golden's config and DBC.
    can_config = os.path.join(SRC, "tests/data/golden/paper_exp2_can/config.yaml")
    out.append(("replay.log_list_dev_zero", [replay, "--config", can_config,
                                             "--log-list", "/dev/zero"]))
    fifo = os.path.join(tmp, "p.log")
    os.mkfifo(fifo)
    out.append(("replay.logs_fifo", [replay, "--config", can_config, "--logs", fifo]))
    out.append(("replay.log_list_nul", [replay, "--config", can_config, "--log-list",
                                        write("nul.list", b"a.log\n\0x\n")]))
    out.append(("replay.log_negative_times", [replay, "--config", can_config, "--log",
                                              write("n.log", "(-50.000000) can0 123#00\n")]))
    out.append(("replay.log_huge_times", [replay, "--config", can_config, "--log", write(
        "h.log", "(9000000000000000.000000) can0 123#00\n")]))
    out.append(("replay.asc_channel_256", [replay, "--config", can_config, "--log", write(
        "c.asc", "date Wed Jan 10 10:55:25.123 am 2024\nbase hex  timestamps absolute\n"
        "   0.015991 256  123  Rx   d 1 01\n")]))
    # --interface: a name the log does not have (the interfaces it has, with their frames), and
    # a name no interface can have.
    two_interfaces = write("i.log", "(1.000000) can0 123#00\n(1.001000) can1 124#00\n"
                                    "(1.002000) can1 125#00\n")
    out.append(("replay.interface_not_in_log", [replay, "--config", can_config, "--log",
                                                two_interfaces, "--interface", "can2"]))
    out.append(("replay.interface_invalid_name", [replay, "--config", can_config, "--log",
                                                  two_interfaces, "--interface", "can 1"]))
    out.append(("vmassd.interface_not_in_log", [vmassd, "--config", can_config, "--replay",
                                                two_interfaces, "--interface", "vcan0", "--speed",
                                                "max", "--no-restore", "--lcm-url", "memq://"]))
    out.append(("vmassd.lcm_url_typo", [vmassd, "--config", config, "--samples", samples,
                                         "--speed", "max", "--no-restore", "--lcm-url",
                                         "udpm://239.255.76.67:7667?tll=0"]))
    out.append(("vmassd.config_lcm_provider", [vmassd, "--config", write(
        "lcm_provider.yaml", BASE_CONFIG + "\nlcm:\n  url: bogus://x\n"), "--samples", samples,
        "--speed", "max", "--no-restore"]))
    # A config vmassd would refuse is refused by vmass-replay too (the same section tables).
    out.append(("replay.config_daemon_section", [replay, "--config", write(
        "daemon_section.yaml", BASE_CONFIG + "\ndaemon:\n  persist_interval_s: 0\n"),
        "--samples", samples]))
    out.append(("replay.config_lcm_key_typo", [replay, "--config", write(
        "lcm_key_typo.yaml", BASE_CONFIG + "\nlcm:\n  urll: udpm://239.255.76.67:7667\n"),
        "--samples", samples]))
    out.append(("replay.known_mass_outside_band", [replay, "--config", config, "--samples",
                                                   samples, "--known-mass", "10:90000"]))
    out.append(("replay.known_mass_malformed", [replay, "--config", config, "--samples",
                                                samples, "--known-mass", "10:1650:-5"]))
    out.append(("replay.stdout_full", [replay, "--config", config, "--samples", samples,
                                       "--out", "-"], "/dev/full"))
    return out


def run(argv, stdout_path=None):
    with open(stdout_path or os.devnull, "wb") as sink:
        p = subprocess.run(argv, stdin=subprocess.DEVNULL,
                           stdout=sink if stdout_path else subprocess.PIPE,
                           stderr=subprocess.PIPE, timeout=60)
    return p.returncode, p.stderr.decode(errors="replace")


def main():
    expected = {}
    table = os.path.join(SRC, "tests/tools/bad_inputs_expected.tsv")
    if not RECORD:
        for line in open(table, encoding="utf-8"):
            if line.strip() and not line.startswith("#"):
                name, code, text = line.rstrip("\n").split("\t", 2)
                expected[name] = (int(code), text)
    failures = 0
    with tempfile.TemporaryDirectory() as tmp:
        all_cases = cases(tmp)
        for name, argv, *stdout_path in all_cases:
            code, err = run(argv, *stdout_path)
            first = err.strip().split("\n")[0] if err.strip() else ""
            if RECORD:
                print(f"{name}\t{code}\t{first[:300]}")
                continue
            if name not in expected:
                print(f"{name}: no expectation in {table}")
                failures += 1
                continue
            want_code, want_text = expected[name]
            text = want_text.replace("TMP", tmp)
            if code != want_code or text not in err:
                print(f"{name}: exit {code} (want {want_code}); stderr:\n{err[:600]}\n"
                      f"  wanted: {text}")
                failures += 1
            if len(err) > 20000:
                print(f"{name}: {len(err)} bytes on stderr: long tokens must be cut")
                failures += 1
        missing = set(expected) - {c[0] for c in all_cases}
        for name in sorted(missing):
            print(f"{name}: expected but no such case")
            failures += 1
        if not RECORD:
            print(f"bad inputs: {len(all_cases) - failures} of {len(all_cases)} cases as expected")
    sys.exit(1 if failures else 0)


if __name__ == "__main__":
    main()
