#!/usr/bin/env bash
# A build that fails shows the compiler's messages: ./lab's progress line reads the build's
# output through a pipe, and under `set -e` with pipefail a failing pipeline once ended the
# script there, silently, after "building: 1 of 12 steps (8%)" (./lab grade, ./lab view).
set -euo pipefail
lab=$1 scratch=$(mktemp -d)
trap 'rm -rf "$scratch"' EXIT
# A cmake that fails as a compiler does: one step done, then an error.
mkdir "$scratch/bin"
cat >"$scratch/bin/cmake" <<'FAKE'
#!/usr/bin/env bash
echo "[1/12] Building CXX object a.o"
echo "tasks/task1_two_masses/spring_damper.cpp:14:3: error: expected ';' before '}' token"
echo "[2/12] FAILED: b.o"
exit 1
FAKE
chmod +x "$scratch/bin/cmake"
# The function alone, as the script defines it, with the script's own say and die, in a shell
# of its own with the script's options (a subshell after `||` would run without set -e).
sed -n '/^say() {/,/^}/p; /^die() {/,/^}/p; /^build_with_progress() {/,/^}/p' "$lab" \
  >"$scratch/functions.sh"
code=0
PATH=$scratch/bin:$PATH BUILD=$scratch bash -c 'set -euo pipefail; source "$1"
  build_with_progress --dir "$2" some-target' - "$scratch/functions.sh" "$scratch" \
  >"$scratch/out" 2>&1 || code=$?
cat "$scratch/out"
[ "$code" -ne 0 ]
grep -q "spring_damper.cpp:14:3: error: expected ';'" "$scratch/out"
grep -q "the build failed" "$scratch/out"
