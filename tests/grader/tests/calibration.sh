#!/usr/bin/env bash
# The reference's times as a grading to the first failure measures them (springlab-grade
# --first-failure, as the mutants are graded): both runs, plain and sanitized, of every test of the
# task, none zero; a cache without the sanitized times would give every later sanitized run only
# the floor's limit. Then --calibrate: it measures another task and keeps the one already there,
# measures nothing twice, is refused with a submission or a grading's option, fails when it
# cannot keep what it measured, and keeps a task another grading wrote while it measured. With a
# copy of the build's kit.toml, so that the cache measured (calibration.txt beside it) is this
# test's own.
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
# Every test of task $1 has a time above 0 in both variants (in the cache $2, by default $cache).
all_timed() {
  local tests timed variant
  tests=$("$(dirname "$grade")/springlab-grade-task$1" --list | grep -c . || true)
  [ "$tests" -gt 0 ] || fail "springlab-grade-task$1 --list names no test"
  for variant in plain sanitized; do
    timed=$(awk -v v="$variant" -v t="$1" '$1 == v && $2 > 0 && $3 == t' "${2:-$cache}" | wc -l)
    [ "$timed" -eq "$tests" ] || fail "$variant: $timed of task $1's $tests tests have a time above 0"
  done
}
all_timed 3
task3=$(awk '$3 == 3' "$cache")
"$grade" --kit "$scratch/kit.toml" --calibrate --tasks 2 --work "$scratch/work" >"$scratch/log" 2>&1 ||
  fail "--calibrate --tasks 2 failed: exit $?"
grep -q "measuring the reference's time per test, task 2 " "$scratch/log" || fail "task 2 not measured"
all_timed 2
[ "$(awk '$3 == 3' "$cache")" = "$task3" ] || fail "--calibrate --tasks 2 did not keep task 3's times"
before=$(cat "$cache")
"$grade" --kit "$scratch/kit.toml" --calibrate --tasks 2,3 --work "$scratch/work" >"$scratch/log" 2>&1 ||
  fail "--calibrate failed: exit $?"
! grep -q "measuring the reference's time" "$scratch/log" || fail "--calibrate measured again"
[ "$(cat "$cache")" = "$before" ] || fail "--calibrate changed the cache it had no need to measure"
status=0
"$grade" --kit "$scratch/kit.toml" --calibrate "$kit/solutions" >"$scratch/log" 2>&1 || status=$?
[ "$status" -eq 2 ] && grep -q "\-\-calibrate grades nothing: give no submission with it" "$scratch/log" ||
  fail "--calibrate with a submission: exit $status"
status=0
"$grade" --kit "$scratch/kit.toml" --calibrate --first-failure >"$scratch/log" 2>&1 || status=$?
[ "$status" -eq 2 ] && grep -Eq -- "--first-failure excludes --calibrate|--calibrate excludes --first-failure" "$scratch/log" ||
  fail "--calibrate --first-failure: exit $status"
# A cache that cannot be written (a folder in its place): exit 1, said.
mkdir -p "$scratch/unwritable/calibration.txt/in-the-way"
cp "$scratch/kit.toml" "$scratch/unwritable/kit.toml"
status=0
"$grade" --kit "$scratch/unwritable/kit.toml" --calibrate --tasks 3 --work "$scratch/work" \
  >"$scratch/log" 2>&1 || status=$?
[ "$status" -eq 1 ] && grep -q "measured but could not be kept in" "$scratch/log" ||
  fail "--calibrate with a cache it cannot write: exit $status"
# Two gradings side by side, each measuring a task of its own: the one that writes last keeps the
# other's task. The other's writing is played by putting task 3's lines in the cache while task 2
# is measured (it prints its first line after reading the cache, and measures for seconds).
mkdir -p "$scratch/side"
cp "$scratch/kit.toml" "$scratch/side/kit.toml"
side=$scratch/side/calibration.txt
"$grade" --kit "$scratch/side/kit.toml" --calibrate --tasks 2 --work "$scratch/side-work" \
  >"$scratch/log" 2>&1 &
measuring=$!
trap 'kill -CONT "$measuring" 2>/dev/null; kill "$measuring" 2>/dev/null || true' EXIT
for _ in $(seq 600); do
  grep -q "measuring the reference's time per test, task 2 " "$scratch/log" && break
  kill -0 "$measuring" 2>/dev/null || break
  sleep 0.1
done
# Stopped while the other grading writes: its own writing cannot come first, however slow this is.
kill -STOP "$measuring" 2>/dev/null || fail "the side run ended before task 3's lines were written"
grep -q "measuring the reference's time per test, task 2 " "$scratch/log" || fail "task 2 not measured"
[ ! -e "$side" ] || fail "the side run wrote its cache before measuring"
{ grep "^task 3 " "$cache"; echo "---"; echo "$task3"; } >"$side.new"
mv "$side.new" "$side"
kill -CONT "$measuring"
wait "$measuring" || fail "--calibrate --tasks 2 beside another grading failed: exit $?"
trap - EXIT
all_timed 2 "$side"
[ "$(awk '$3 == 3' "$side")" = "$task3" ] && grep -q "^task 3 " "$side" ||
  fail "a grading measuring task 2 dropped task 3, written meanwhile by another"
echo "calibration: ok: both variants of every test of tasks 3 (to the first failure) and 2" \
  "(--calibrate), the others kept (also those written meanwhile), none measured twice, a" \
  "cache it cannot write an error"
