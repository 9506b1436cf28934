#!/usr/bin/env bash
# Measures grading speed (figures only, no verdict): one submission from a warm build, then a
# class of N, every submission different in every task (a comment naming the student is added to
# each of the solutions' files, so no two task copies are alike and nothing is graded once for
# two). Usage: tests/grader/measure_class.sh [N] (default 30), from the kit's folder, after
# `./lab grade --help` has built the grader.
set -euo pipefail
cd "$(dirname "$0")/../.."
count=${1:-30}
grade=build/dev/tests/grader/springlab-grade
scratch=$(mktemp -d)
trap 'rm -rf "$scratch"' EXIT

make_class() {  # make_class FIRST LAST: students FIRST..LAST
  local i f
  for i in $(seq "$1" "$2"); do
    cp -r solutions "$scratch/student$i"
    for f in "$scratch/student$i"/task*/*.cpp; do echo "// student $i" >>"$f"; done
  done
}

seconds() {  # seconds COMMAND...: runs it, prints its wall time in seconds
  local start end
  start=$(date +%s.%N)
  "$@" >"$scratch/log" 2>&1 || { cat "$scratch/log"; exit 1; }
  end=$(date +%s.%N)
  awk -v a="$start" -v b="$end" 'BEGIN { printf "%.1f", b - a }' 
}

"$grade" --out "$scratch/results" solutions >/dev/null 2>&1  # the reference's times, measured once
make_class 0 "$count"
one=$(seconds "$grade" --out "$scratch/results" "$scratch/student0")
class=()
for i in $(seq 1 "$count"); do class+=("$scratch/student$i"); done
all=$(seconds "$grade" --out "$scratch/results" "${class[@]}")
grep -q "^\[$count/$count\]" "$scratch/log" || { cat "$scratch/log"; exit 1; }
echo "machine: $(nproc) processors ($(awk -F ': ' '/^model name/ { print $2; exit }' /proc/cpuinfo))"
echo "one submission from a warm build: $one s"
echo "a class of $count, all different: $all s, $(awk -v a="$all" -v n="$count" 'BEGIN { printf "%.1f", a / n }') s each"
