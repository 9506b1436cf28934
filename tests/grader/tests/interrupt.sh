#!/usr/bin/env bash
# A grading run stopped half way (Ctrl-C, kill, kill -9) leaves no process behind: the test that
# was running sleeps (std::this_thread::sleep_for, so no processor-time limit would end it), and
# within 5 s of the signal every process the grader had started must be gone. SIGINT and SIGTERM
# end the grader with 128 + the signal and a sentence; the results of the submission graded before
# are kept, and a second run with the same --out keeps them without grading them again.
# Usage: interrupt.sh GRADE KIT SCRATCH SIGNAL
set -euo pipefail
grade=$1 kit=$2 scratch=$3 signal=$4
fail() { echo "interrupt ($signal): $*" >&2; [ ! -f "$scratch/log" ] || cat "$scratch/log" >&2; exit 1; }
rm -rf "$scratch"
mkdir -p "$scratch"
cp -r "$kit/solutions" "$scratch/early"
cp -r "$kit/solutions" "$scratch/sleeper"
f=$scratch/sleeper/task1_two_masses/spring_damper.cpp
sed -i 's|#include "springlab/task1_two_masses.hpp"|&\n#include <chrono>\n#include <thread>|; 0,/const Vec2 d = r_p - r_q;/s||std::this_thread::sleep_for(std::chrono::seconds(1000));\n  const Vec2 d = r_p - r_q;|' "$f"
grep -q sleep_for "$f" || fail "the sleeper was not made"
# The first submission alone, so that its results exist before the sleeper starts.
"$grade" --tasks 1 --jobs 1 --out "$scratch/results" --work "$scratch/work" "$scratch/early" \
  >"$scratch/log" 2>&1 || fail "the first run failed"
descendants() {  # every process under $1
  local p
  for p in $(cat /proc/"$1"/task/*/children 2>/dev/null); do echo "$p"; descendants "$p"; done
}
set -m  # a background job keeps SIGINT
"$grade" --tasks 1 --jobs 1 --out "$scratch/results" --work "$scratch/work" "$scratch/early" \
  "$scratch/sleeper" >"$scratch/log" 2>&1 &
grader=$!
set +m
started=()
for _ in $(seq 600); do  # until a test of the sleeper sleeps: a worker process under the grader
  mapfile -t started < <(descendants "$grader")
  for p in "${started[@]}"; do
    [[ $(cat /proc/"$p"/cmdline 2>/dev/null | tr '\0' ' ') == *--work* ]] && break 2
  done
  sleep 0.1
done
[ "${#started[@]}" -gt 0 ] || fail "no test started"
sleep 1
mapfile -t started < <(descendants "$grader")
kill -s "$signal" "$grader"
status=0
wait "$grader" || status=$?
left=()
for _ in $(seq 50); do
  left=()
  for p in "${started[@]}"; do [ -d /proc/"$p" ] && left+=("$p"); done
  [ "${#left[@]}" -eq 0 ] && break
  sleep 0.1
done
[ "${#left[@]}" -eq 0 ] ||
  fail "${#left[@]} of the ${#started[@]} processes it had started still run 5 s later: $(ps -o pid=,args= -p "$(IFS=,; echo "${left[*]}")" | cut -c1-100 | tr '\n' ';')"
case $signal in
  INT) want=130 ;;
  TERM) want=143 ;;
  KILL) want=137 ;;
esac
[ "$status" -eq "$want" ] || fail "exit $status, not $want"
if [ "$signal" != KILL ]; then
  grep -q "stopped by .*run the same command again to grade the rest" "$scratch/log" ||
    fail "no sentence about the stop"
fi
# The run again, without the sleeper: the first submission is kept as it was.
"$grade" --tasks 1 --out "$scratch/results" --work "$scratch/work" "$scratch/early" \
  >"$scratch/log" 2>&1 || fail "the second run failed"
grep -q "graded before with the same files, kit and settings: kept" "$scratch/log" ||
  fail "the second run graded the first submission again"
echo "interrupt ($signal): ok: ${#started[@]} processes ended, exit $status"
