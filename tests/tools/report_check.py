"""What the accuracy report's table tests share: the report run on rows written as JSON lines,
and the lines it must hold."""
import json
import subprocess
import sys


def report_text(report, option, rows, path):
    """vmass-accuracy-report OPTION PATH --out -, PATH holding the rows; its text."""
    with open(path, "w", encoding="utf-8") as f:
        f.writelines(json.dumps(r) + "\n" for r in rows)
    return subprocess.run([sys.executable, report, option, path, "--out", "-"],
                          check=True, capture_output=True, text=True).stdout


def check(text, expected):
    """Exits naming the lines of `expected` the text lacks, with the text."""
    missing = [e for e in expected if e not in text]
    if missing:
        sys.exit("missing from the report:\n" + "\n".join(missing) + "\n--- report:\n" + text)
