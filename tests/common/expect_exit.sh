#!/bin/sh
# expect_exit.sh EXIT_CODE REGEX COMMAND [ARGS...]: runs the command; fails unless it exits with
# EXIT_CODE and (REGEX not empty) its output (stdout and stderr) matches REGEX (grep -E).
expected=$1
regex=$2
shift 2
out=$("$@" 2>&1)
rc=$?
if [ "$rc" -ne "$expected" ]; then
  printf 'FAIL: exit %s, expected %s: %s\n%s\n' "$rc" "$expected" "$*" "$out" | head -c 4000
  exit 1
fi
if [ -n "$regex" ] && ! printf '%s\n' "$out" | grep -Eq -- "$regex"; then
  printf 'FAIL: output does not match /%s/: %s\n%s\n' "$regex" "$*" "$out" | head -c 4000
  exit 1
fi
echo "ok: exit $rc${regex:+, /$regex/}"
