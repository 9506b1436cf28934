#!/usr/bin/env bash
# ./lab test's closing table reads every test of the tree's JUnit file. With pipefail on, a
# reader that stops after five lines made the sort before it die of SIGPIPE once the list passed a
# pipe's buffer (64 KiB): `./lab test` then failed with exit 141 after every test had passed.
set -euo pipefail
lab=$1 scratch=$(mktemp -d)
trap 'rm -rf "$scratch"' EXIT
for i in $(seq 3000); do
  echo "<testcase name=\"suite.case $i, named at length to fill the pipe sooner\" time=\"$i.5\"/>"
done >"$scratch/suite-junit.xml"
# The function alone, as the script defines it.
source <(sed -n '/^slowest_tests() {/,/^}/p' "$lab")
slowest_tests "$scratch/suite-junit.xml" >"$scratch/out"
cat "$scratch/out"
[ "$(grep -c ' s  suite.case ' "$scratch/out")" -eq 5 ]
grep -q '^ *3000.5 s  suite.case 3000, ' "$scratch/out"
# The batch's table: printed from the test's output, and nothing (not a failure) without it.
source <(sed -n '/^batch_phases() {/,/^}/p' "$lab")
[ -z "$(batch_phases "$scratch/suite-junit.xml")" ]
printf '<system-out>grader.batch: 2 submissions\ngrader.batch:  compile  4 in 8.0 s &amp; so on\n' \
  >"$scratch/batch.xml"
printf '<system-out>grader.mutants: 3 mutants graded apart\n' >>"$scratch/batch.xml"
batch_phases "$scratch/batch.xml" >"$scratch/phases"
grep -qx "    grader.batch:  compile  4 in 8.0 s & so on" "$scratch/phases"
[ "$(tail -n 1 "$scratch/phases")" = "    grader.mutants: 3 mutants graded apart" ]
