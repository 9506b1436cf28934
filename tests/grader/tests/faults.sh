#!/usr/bin/env bash
# The grader under the faults an instructor meets in a term, in one class of 30 graded as nobody
# (as the Gradescope autograder grades): one submission folder it may not read, one that vanishes
# after it was found, one whose copy does not fit in the work folder's disk (a tmpfs that 60 MB of
# its files fill). The other 27 are graded right; the three are named "not graded" (in the
# gradebook, review.csv and on the terminal) and the run exits 3. Then a late submission graded
# into the same --out replaces nothing but its own row: the other 30 are kept. Then --out on a full
# disk: exit 3 and "cannot write", never a silent loss. Needs root (a tmpfs is mounted).
# Usage: faults.sh GRADE KIT SCRATCH
set -euo pipefail
grade=$1 kit=$2 scratch=$3
[ "$(id -u)" -eq 0 ] || { echo "faults: skipped: needs root to mount a tmpfs"; exit 77; }
fail() { echo "faults: $*" >&2; [ ! -f "$scratch/log" ] || tail -n 40 "$scratch/log" >&2; exit 1; }
cleanup() { umount "$scratch/disk" 2>/dev/null || true; umount "$scratch/full" 2>/dev/null || true; }
trap cleanup EXIT
cleanup
rm -rf "$scratch"
mkdir -p "$scratch/class" "$scratch/disk" "$scratch/full"
# Three different copies among the 27 (equal copies share one build): builds still run side by
# side on the small work disk while the faults happen, with 3 builds instead of 27 (issue 27:
# the test took 129 s with 27 different copies, 41 s with three, 33 s with one, each run alone).
for i in $(seq -w 1 27); do
  cp -r "$kit/solutions" "$scratch/class/student$i"
  echo "// copy $((10#$i % 3))" >>"$scratch/class/student$i/task1_two_masses/spring_damper.cpp"
done
cp -r "$kit/solutions" "$scratch/class/unreadable"
chmod 000 "$scratch/class/unreadable"
cp -r "$kit/solutions" "$scratch/class/vanishing"
cp -r "$kit/solutions" "$scratch/class/too-big"
for i in $(seq 1 60); do head -c 1000000 /dev/zero >"$scratch/class/too-big/task1_two_masses/data$i.bin"; done
# Root without the right to mount (a container, a root without util-linux's mount) skips too.
mount -t tmpfs -o size=48m tmpfs "$scratch/disk" ||
  { echo "faults: skipped: cannot mount a tmpfs"; exit 77; }
chmod 777 "$scratch" "$scratch/class" "$scratch/disk" "$scratch/full"
as_nobody=(setpriv --reuid=65534 --regid=65534 --clear-groups)
# The reference's times measured again, so that the vanishing folder can go while they are: with a
# copy of the build's kit.toml, whose cache of times (calibration.txt beside it) starts empty; the
# build's own cache, which the gradings running beside this test read, is left alone.
cp "$(dirname "$grade")/kit.toml" "$scratch/kit.toml"
kit_toml=(--kit "$scratch/kit.toml")
"${as_nobody[@]}" "$grade" "${kit_toml[@]}" --tasks 1 --out "$scratch/results" \
  --work "$scratch/disk/work" "$scratch"/class/* >"$scratch/log" 2>&1 &
g=$!
for _ in $(seq 600); do grep -q "measuring the reference's time" "$scratch/log" && break; sleep 0.1; done
rm -rf "$scratch/class/vanishing"
status=0
wait "$g" || status=$?
[ "$status" -eq 3 ] || fail "exit $status, not 3"
book=$scratch/results/gradebook.csv
[ "$(grep -c '^student[0-9]*,14,,,,,14$' "$book")" -eq 27 ] || fail "not 27 full rows: $(cat "$book")"
for name in unreadable vanishing too-big; do
  grep -q "^$name,not graded,,,,,not graded$" "$book" || fail "$name is not 'not graded' in the gradebook"
  grep -Eq "^$name,1,\"?not graded: " "$scratch/results/review.csv" || fail "review.csv does not name $name"
  grep -q "^  $name: task 1: " "$scratch/log" || fail "the run's output does not name $name"
done
grep -q "^  too-big: task 1: the grader.s work folder .* is full" "$scratch/log" || fail "too-big: not the full disk"
grep -q "^  unreadable: .*Permission denied" "$scratch/log" || fail "unreadable: not its permission"
# A late submission into the class's folder: its row added, the other 29 kept.
cp -r "$kit/solutions" "$scratch/late"
chmod -R a+rX "$scratch/late"
"${as_nobody[@]}" "$grade" "${kit_toml[@]}" --tasks 1 --out "$scratch/results" \
  --work "$scratch/disk/work" "$scratch/late" >"$scratch/log" 2>&1 || fail "the late submission: exit $?"
[ "$(($(wc -l <"$book") - 1))" -eq 31 ] || fail "the gradebook does not hold 31 rows: $(cat "$book")"
grep -q '^late,14,,,,,14$' "$book" || fail "the late submission's row is missing"
grep -q "holds 30 other submissions' results of earlier runs: kept" "$scratch/log" ||
  fail "the kept results were not said"
# --out on a disk with no room for the gradebook: said, exit 3.
mount -t tmpfs -o size=4k tmpfs "$scratch/full"
chmod 777 "$scratch/full"
status=0
"${as_nobody[@]}" "$grade" "${kit_toml[@]}" --tasks 1 --out "$scratch/full/results" \
  --work "$scratch/disk/work" "$scratch/late" >"$scratch/log" 2>&1 || status=$?
[ "$status" -eq 3 ] && grep -q "cannot write .*: No space left on device" "$scratch/log" ||
  fail "a full --out: exit $status"
echo "faults: ok: 27 of 30 graded, the three named, exit 3; a late one kept the other 30 rows; a full --out said so"
