#!/usr/bin/env bash
# The reference's times as a grading to the first failure measures them (springlab-grade
# --first-failure, as the mutants are graded): both runs, plain and sanitized, of every test of the
# task, none zero; a cache without the sanitized times would give every later sanitized run only
# the floor's limit. Then --calibrate with the times already there measures nothing again, and
# with a submission is refused. With a copy of the build's kit.toml, so that the cache measured
# (calibration.txt beside it) is this test's own.
# Usage: calibration.sh GRADE KIT SCRATCH
set -euo pipefail
grade=$1 kit=$2 scratch=$3
fail() { echo "calibration: $*" >&2; [ ! -f "$scratch/log" ] || tail -n 30 "$scratch/log" >&2; exit 1; }
rm -rf "$scratch"
mkdir -p "$scratch"
cp "$(dirname "$grade")/kit.toml" "$scratch/kit.toml"
cache=$scratch/calibration.txt
# Task 3: the fewest tests and one file.
"$grade" --kit "$scratch/kit.toml" --first-failure --tasks 3 --out "$scratch/results" \
  --work "$scratch/work" "$kit/solutions" >"$scratch/log" 2>&1 || fail "the grading failed: exit $?"
grep -q "measuring the reference's time per test, task 3 " "$scratch/log" || fail "nothing was measured"
tests=$("$(dirname "$grade")/springlab-grade-task3" --list | grep -c .)
[ "$tests" -gt 0 ] || fail "springlab-grade-task3 --list names no test"
for variant in plain sanitized; do
  timed=$(awk -v v="$variant" '$1 == v && $2 > 0 && $3 == 3' "$cache" | wc -l)
  [ "$timed" -eq "$tests" ] || fail "$variant: $timed of task 3's $tests tests have a time above 0"
done
before=$(cat "$cache")
"$grade" --kit "$scratch/kit.toml" --calibrate --tasks 3 --work "$scratch/work" >"$scratch/log" 2>&1 ||
  fail "--calibrate failed: exit $?"
! grep -q "measuring the reference's time" "$scratch/log" || fail "--calibrate measured task 3 again"
[ "$(cat "$cache")" = "$before" ] || fail "--calibrate changed the cache it had no need to measure"
status=0
"$grade" --kit "$scratch/kit.toml" --calibrate "$kit/solutions" >"$scratch/log" 2>&1 || status=$?
[ "$status" -eq 2 ] && grep -q "\-\-calibrate grades nothing: give no submission with it" "$scratch/log" ||
  fail "--calibrate with a submission: exit $status"
echo "calibration: ok: plain and sanitized times for all $tests tests of task 3, none measured twice"
