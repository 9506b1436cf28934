#!/usr/bin/env bash
# The grader where namespaces cannot be had, as in a container whose profile refuses them (what
# Gradescope's may do): springlab-grade runs inside a user namespace in which bubblewrap has
# disabled making more (--disable-userns), as nobody when this test runs as root, as the
# Gradescope autograder runs it. It must say once, on its output and in review.csv, that it has no
# sandbox and why; grade the solutions of task 3 fully; and give nothing, and show nothing of the
# grader's environment or the kit's solution, to a submission that looks for them.
# Usage: no_namespaces.sh GRADE KIT SCRATCH
set -euo pipefail
grade=$1 kit=$2 scratch=$3
fail() { echo "no_namespaces: $*" >&2; [ ! -f "$scratch/log" ] || cat "$scratch/log" >&2; exit 1; }
rm -rf "$scratch"
mkdir -p "$scratch/solutions" "$scratch/reader/task3_shear_springs"
cp -r "$kit/solutions/task3_shear_springs" "$scratch/solutions/"
sed "s|@KIT@|$kit|g" "$kit/tests/grader/hostile/read-grader-environment/shear_springs.cpp" \
  >"$scratch/reader/task3_shear_springs/shear_springs.cpp"
chmod -R a+rwX "$scratch"
as_user=()
[ "$(id -u)" -ne 0 ] || as_user=(setpriv --reuid=65534 --regid=65534 --clear-groups)
status=0
SPRINGLAB_BATCH_SECRET=no-namespaces-secret-51d2 "${as_user[@]}" bwrap --unshare-user \
  --disable-userns --bind / / --proc /proc --dev /dev -- \
  "$grade" --tasks 3 --out "$scratch/results" --work "$scratch/work" "$scratch/solutions" \
  "$scratch/reader" >"$scratch/log" 2>&1 || status=$?
[ "$status" -eq 0 ] || fail "springlab-grade exited $status"
[ "$(grep -c '^springlab-grade: no sandbox: namespaces cannot be had here' "$scratch/log")" -eq 1 ] ||
  fail "the run's output does not say once that there is no sandbox"
grep -q '^(every submission),,"no sandbox: namespaces cannot be had here' "$scratch/results/review.csv" ||
  fail "review.csv does not say that there is no sandbox"
grep -q '^solutions,,,9,,,9$' "$scratch/results/gradebook.csv" || fail "the solutions lost points"
grep -q '^reader,,,0,,,0$' "$scratch/results/gradebook.csv" || fail "the reader got points"
grep -q 'environment of ' "$scratch/results/reader/feedback.txt" || fail "the reader did not run"
! grep -q -e 'no-namespaces-secret-51d2' -e 'root:' -e 'index(row + 1, col + 1)' \
  "$scratch/results/reader/feedback.txt" || fail "the reader's feedback shows what it may not see"
echo "no_namespaces: ok: $(grep -m1 '^springlab-grade: no sandbox' "$scratch/log" | cut -c1-140)..."
