#!/usr/bin/env bash
# The grader where namespaces cannot be had, as in a container whose profile refuses them (what
# Gradescope's may do), graded twice:
# - as nobody: springlab-grade runs inside a user namespace in which bubblewrap has disabled
#   making more (--disable-userns), as nobody when this test runs as root, as the Gradescope
#   autograder runs it; every command then runs as the grader's own user;
# - as root (when this test is): bubblewrap out of the grader's sight, so that commands run as
#   users apart (65000 and up, one per command running at once).
# Each time it must say once, on its output and in review.csv, that it has no sandbox and why;
# grade the solutions of task 3 fully; give nothing, and show nothing of the grader's environment
# or the kit's solution, to a submission that looks for them; and hold against a submission that
# signals the grader and every other test of the run, from its tests and from its compiler: the
# grader finishes, a slow correct submission graded beside it keeps full marks, the attacker gets
# nothing. No compile-time code of the submission's own can run (the policy refuses plugins'
# flags, pragmas, attributes, asm; the kit's flags are fixed), so the compiler stands in for a
# compromised one: kit.toml's compile command is a script that tries, once, for the attacker.
# Usage: no_namespaces.sh GRADE KIT SCRATCH
set -euo pipefail
grade=$1 kit=$2 scratch=$3
log=$scratch/log
fail() { echo "no_namespaces: $*" >&2; [ ! -f "$log" ] || cat "$log" >&2; exit 1; }
rm -rf "$scratch"
mkdir -p "$scratch/solutions" "$scratch/reader/task3_shear_springs" \
  "$scratch/sleeper/task3_shear_springs" "$scratch/attacker/task3_shear_springs" "$scratch/kit"
cp -r "$kit/solutions/task3_shear_springs" "$scratch/solutions/"
sed "s|@KIT@|$kit|g" "$kit/tests/grader/hostile/read-grader-environment/shear_springs.cpp" \
  >"$scratch/reader/task3_shear_springs/shear_springs.cpp"
sed "s|@SCRATCH@|$scratch|g" "$kit/tests/grader/tests/no_namespaces/kill_every_process.cpp" \
  >"$scratch/attacker/task3_shear_springs/shear_springs.cpp"
# The sleeper: the solution, a fifth of a second slower per call, so that its tests are there to
# be found.
sed -e 's|^#include "springlab/task3_shear_springs.hpp"|&\n#include <chrono>\n#include <thread>|' \
  -e '/springlab::shear_springs(/,/) {$/ s|) {$|) {\n  std::this_thread::sleep_for(std::chrono::milliseconds(200));|' \
  "$kit/solutions/task3_shear_springs/shear_springs.cpp" \
  >"$scratch/sleeper/task3_shear_springs/shear_springs.cpp"
grep -q sleep_for "$scratch/sleeper/task3_shear_springs/shear_springs.cpp" ||
  fail "the sleeper was not made from the solution"

# The kit as built, but its compiler a script that does, for the attacker, what a compromised
# compiler could: signal the grader (its parent) and every test of this run it can find, each
# attempt written to compiler.log; then it compiles.
built=$(dirname "$grade")
cp "$built/calibration.txt" "$scratch/kit/"
sed "s|^compile = \[\"[^\"]*\"|compile = [\"$scratch/kit/c++\"|" "$built/kit.toml" \
  >"$scratch/kit/kit.toml"
cat >"$scratch/kit/c++" <<EOF
#!/bin/bash
if grep -qs 'target: the grader' -- "\$@" && mkdir "$scratch/attacked" 2>/dev/null; then
  log=$scratch/compiler.log
  echo "grader \$PPID" >>"\$log"
  kill -KILL "\$PPID" 2>>"\$log" && echo "KILLED the grader" >>"\$log"
  for _ in \$(seq 300); do  # 30 s at most for a test of this run to be running
    tests=\$(pgrep -f "springlab-grade-task3 --run .*$scratch/" || true)
    [ -z "\$tests" ] || break
    sleep 0.1
  done
  for pid in \$tests; do
    echo "test \$pid" >>"\$log"
    kill -KILL "\$pid" 2>>"\$log" && echo "KILLED a test" >>"\$log"
    kill -KILL -- "-\$pid" 2>>"\$log" && echo "KILLED a test's group" >>"\$log"
  done
  [ -n "\$tests" ] || echo "saw no test" >>"\$log"
fi
exec /usr/bin/c++ "\$@"
EOF
chmod -R a+rwX "$scratch"
chmod 755 "$scratch/kit/c++"

# Grades the four submissions with springlab-grade started as `runner` says, and checks the
# results; $1 names the mode.
grade_without_namespaces() {
  local mode=$1 out=$scratch/$1
  shift
  rm -rf "$scratch/attacked" "$scratch/compiler.log" "$scratch/work"
  local status=0
  SPRINGLAB_BATCH_SECRET=no-namespaces-secret-51d2 "$@" "$grade" --kit "$scratch/kit/kit.toml" \
    --tasks 3 --out "$out" --work "$scratch/work" "$scratch/solutions" "$scratch/reader" \
    "$scratch/sleeper" "$scratch/attacker" >"$log" 2>&1 || status=$?
  [ "$status" -eq 0 ] || fail "$mode: springlab-grade exited $status"
  [ "$(grep -c '^springlab-grade: no sandbox: namespaces cannot be had here' "$log")" -eq 1 ] ||
    fail "$mode: the run's output does not say once that there is no sandbox"
  grep -q '^(every submission),,"no sandbox: namespaces cannot be had here' "$out/review.csv" ||
    fail "$mode: review.csv does not say that there is no sandbox"
  grep -q '^solutions,,,9,,,9$' "$out/gradebook.csv" || fail "$mode: the solutions lost points"
  grep -q '^sleeper,,,9,,,9$' "$out/gradebook.csv" || fail "$mode: the sleeper lost points"
  grep -q '^reader,,,0,,,0$' "$out/gradebook.csv" || fail "$mode: the reader got points"
  grep -q '^attacker,,,0,,,0$' "$out/gradebook.csv" || fail "$mode: the attacker got points"
  grep -q 'environment of ' "$out/reader/feedback.txt" || fail "$mode: the reader did not run"
  ! grep -q -e 'no-namespaces-secret-51d2' -e 'root:' -e 'index(row + 1, col + 1)' \
    "$out/reader/feedback.txt" || fail "$mode: the reader's feedback shows what it may not see"
  # The attacker's tests: each stopped at its first signal to another process, the grader and
  # other tests both tried.
  local feedback=$out/attacker/feedback.txt
  grep -q 'target: the grader' "$feedback" || fail "$mode: no test of the attacker tried the grader"
  grep -q 'target: another test' "$feedback" || fail "$mode: no test of the attacker tried another"
  [ "$(grep -c 'signal other processes' "$feedback")" -ge 2 ] ||
    fail "$mode: the attacker's signals were not stopped: $(cat "$feedback")"
  # Its compiler: every signal refused.
  local tried
  tried=$(cat "$scratch/compiler.log" 2>/dev/null) || fail "$mode: the attacker's compiler never ran"
  grep -q '^grader ' <<<"$tried" && grep -q '^test ' <<<"$tried" ||
    fail "$mode: the attacker's compiler did not try the grader and a test: $tried"
  ! grep -q KILLED <<<"$tried" || fail "$mode: the attacker's compiler signalled: $tried"
  [ "$(grep -c 'Operation not permitted' <<<"$tried")" -eq $((1 + 2 * $(grep -c '^test ' <<<"$tried"))) ] ||
    fail "$mode: not every signal of the attacker's compiler was refused: $tried"
  echo "no_namespaces: $mode: ok: the attacker's compiler tried $(grep -c '^test ' <<<"$tried") test(s)" \
    "and the grader, its tests $(grep -c 'signal other processes' "$feedback") times; " \
    "$(grep -m1 '^springlab-grade: no sandbox' "$log" | cut -c1-120)..."
}

as_nobody=()
[ "$(id -u)" -ne 0 ] || as_nobody=(setpriv --reuid=65534 --regid=65534 --clear-groups)
grade_without_namespaces nobody "${as_nobody[@]}" bwrap --unshare-user --disable-userns --bind / / \
  --proc /proc --dev /dev --
if [ "$(id -u)" -eq 0 ]; then
  # bubblewrap hidden behind an empty, unexecutable file: the grader finds none.
  grade_without_namespaces root bwrap --dev-bind / / --ro-bind /dev/null "$(command -v bwrap)" --
  grep -q 'users 65000-65533 (one per command running at once)' "$log" ||
    fail "root: commands did not run as users apart"
fi
