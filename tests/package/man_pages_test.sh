#!/bin/sh
# The man pages help2man built (packaging/CMakeLists.txt, packaging/man/TOOL.h2m): every installed
# tool's page has what a person operating a vehicle PC looks for, and renders without a warning:
#   - NAME (a real one, not help2man's "manual page for"), SYNOPSIS, DESCRIPTION, OPTIONS,
#     EXIT STATUS (0, 1 or 2 explained), FILES, ENVIRONMENT, EXAMPLES, SEE ALSO
#   - vmassd's SIGNALS (SIGTERM, SIGINT, SIGHUP); vmass-can's subcommands' options; vmass-plot's
#     SYNOPSIS (argparse says "usage:", which help2man does not take)
#   man_pages_test.sh MAN_DIR TOOL...
set -u
dir=$1
shift
fail() { echo "FAIL: $*"; exit 1; }
has_section() { grep -q "^\.SH \"\{0,1\}$2\"\{0,1\}\$" "$1"; }

for tool in "$@"; do
  page=$dir/$tool.1
  [ -s "$page" ] || fail "no page $page"
  for section in NAME SYNOPSIS DESCRIPTION OPTIONS "EXIT STATUS" FILES ENVIRONMENT EXAMPLES \
      "SEE ALSO"; do
    has_section "$page" "$section" || fail "$tool.1 has no $section section: $(grep '^\.SH' "$page")"
  done
  sed -n '/^\.SH NAME/,/^\.SH/p' "$page" | grep -q "manual page for" &&
    fail "$tool.1: help2man's placeholder NAME"
  sed -n '/^\.SH "EXIT STATUS"/,/^\.SH/p' "$page" | grep -q '^\.B 0' ||
    fail "$tool.1: EXIT STATUS without status 0"
  sed -n '/^\.SH SYNOPSIS/,/^\.SH/p' "$page" | grep -q "$tool" ||
    fail "$tool.1: SYNOPSIS without the command"
  warnings=$(LC_ALL=C.UTF-8 groff -t -man -Tutf8 -ww -z "$page" 2>&1)
  [ -z "$warnings" ] || fail "$tool.1: groff warns: $warnings"
  MANWIDTH=80 man -l "$page" 2>/dev/null | grep -q "^EXIT STATUS" || fail "$tool.1: man -l"
done
echo "ok: $# pages with NAME, SYNOPSIS, OPTIONS, EXIT STATUS, FILES, ENVIRONMENT, EXAMPLES, SEE ALSO"

for signal in SIGTERM SIGINT SIGHUP; do
  sed -n '/^\.SH SIGNALS/,/^\.SH/p' "$dir/vmassd.1" | grep -q "$signal" ||
    fail "vmassd.1: SIGNALS lacks $signal"
done
echo "ok: vmassd.1 has SIGNALS"
# vmass-can: each subcommand's own options (check --strict, decode --json, dump --idle-timeout).
for option in strict json idle\\\\-timeout interface; do
  grep -q "^\\\\fB\\\\-\\\\-$option" "$dir/vmass-can.1" || fail "vmass-can.1 lacks --$option"
done
echo "ok: vmass-can.1 has its subcommands' options"
sed -n '/^\.SH SYNOPSIS/,/^\.SH/p' "$dir/vmass-plot.1" | grep -q "\-\-estimates" ||
  fail "vmass-plot.1: SYNOPSIS without its options"
echo "ok: vmass-plot.1 has a SYNOPSIS"
