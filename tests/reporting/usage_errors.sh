#!/bin/sh
# usage_errors.sh PROGRAM 'ARGS' ... — every frontsteal executable's command-line contract (reporting/
# command_line.hpp): --help prints the options and exits 0; each ARGS (one bad command line, words split on
# spaces) exits 2 with a message on stderr that names its first word (the flag at fault).
program=$1
shift
help=$("$program" --help) || { echo "FAIL: $program --help exited $?"; exit 1; }
echo "$help" | grep -q -- '--help' || { echo "FAIL: $program --help does not list its options"; exit 1; }
for args in "$@"; do
  # shellcheck disable=SC2086  # word splitting of ARGS is the point
  message=$("$program" $args 2>&1 >/dev/null)
  status=$?
  flag=${args%% *}
  if [ "$status" -ne 2 ]; then echo "FAIL: $program $args: exit $status, expected 2"; exit 1; fi
  if ! echo "$message" | grep -q -- "$flag"; then echo "FAIL: $program $args: message does not name $flag: $message"; exit 1; fi
  echo "ok: $program $args -> exit 2: $message" | head -1
done
