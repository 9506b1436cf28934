#!/usr/bin/env bash
# ./lab runs under macOS's /bin/bash 3.2 (issue 36). No bash 3.2 is packaged for Debian, so this
# refuses what bash 3.2 does not have, in the files given: associative arrays, case changes in
# expansions (${x^^}), mapfile, namerefs, wait -n, |& and &>>, ;;&, coproc, ${x@...}, and an
# array expanded bare where it may be empty under set -u ("${sudo[@]}": "unbound variable" before
# bash 4.4; write ${sudo[@]+"${sudo[@]}"}). The kit's authors also ran lab's student commands under
# a bash 3.2.48 built from source (README.md, "Set-up").
set -euo pipefail
status=0
check() {  # check FILE REGEX WHAT
  local hits
  hits=$(grep -nE "$2" "$1" | grep -v '^[0-9]*: *#' || true)
  if [ -n "$hits" ]; then
    printf '%s: %s (bash 3.2 has none):\n%s\n' "$1" "$3" "$hits"
    status=1
  fi
}
for file in "$@"; do
  check "$file" '(local|declare|typeset) +-[a-zA-Z]*[An]' "associative arrays or namerefs"
  check "$file" '\$\{[!#]?[A-Za-z_][A-Za-z_0-9]*(\[[^]]*\])?(\^|,|@[A-Za-z])' "case changes or @ operators in expansions"
  check "$file" '(^|[^A-Za-z_])(mapfile|readarray|coproc)([^A-Za-z_]|$)' "mapfile, readarray or coproc"
  check "$file" 'wait +-n' "wait -n"
  check "$file" '\|&|&>>|;;&' "|&, &>> or ;;&"
  check "$file" '(^|[^+])"\$\{(sudo|missing|pids|extra|args)\[@\]\}"' "an array that may be empty, bare"
done
[ "$status" -eq 0 ] && echo "bash 3.2: none of the constructs it lacks in $*"
exit "$status"
