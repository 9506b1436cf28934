#!/usr/bin/env bash
# Gradescope runs this once, as root, when it builds the autograder's image from the zip of
# ./lab autograder (unzipped into /autograder/source, the kit in springlab/ beside this file):
# it installs what the kit needs with the kit's own ./lab setup, builds the grader, lets it measure
# the reference's time per test once (build/dev/tests/grader/calibration.txt, so that each
# submission's run only grades), and hides the solutions, the mutants and the hidden tests from the
# user run_autograder grades as.
#
# Debian 12 has everything the kit needs. Gradescope's default image, Ubuntu 22.04, lacks three
# things, which are made up for here, each with a message: CMake 3.25 (apt has 3.22: CMake 3.x
# from PyPI, with pip), toml++ (no package: the kit's CMake downloads its 3.4.0 release) and
# GCC 12 (the default g++ is 11: g++-12 from apt). Ubuntu 24.04 has every package (Catch2 3,
# GCC 13, CMake 3.28), as Debian 13 does, where CI runs this script (.ci/platforms/run
# gradescope); Ubuntu 22.04's path was never run by the kit's authors (README.md, "Gradescope").
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
KIT=$here/springlab
started=$(date +%s)

say() { printf '==> setup.sh: %s\n' "$*"; }
die() {
  printf 'setup.sh: %s\n' "$*" >&2
  exit 1
}

[ -x "$KIT/lab" ] || die "no kit in $KIT: the zip of ./lab autograder has it in springlab/"
command -v apt-get >/dev/null ||
  die "apt-get is missing: the kit installs with apt (choose Gradescope's Ubuntu 22.04 base image)"
sudo=()
[ "$(id -u)" -eq 0 ] || sudo=(sudo)

# True when version $1 is $2 or newer ("" is older than anything).
at_least() { [ "$(printf '%s\n%s\n' "$2" "$1" | sort -V | head -n 1)" = "$2" ]; }
installed() { dpkg-query -W -f='${Status}' "$1" 2>/dev/null | grep -q 'ok installed'; }
updated=0
apt_update() {
  [ $updated -eq 1 ] || "${sudo[@]}" apt-get update -q
  updated=1
}
# The version apt would install of package $1, without its revision; "" when it has none (after
# apt_update, which a subshell could not record).
apt_version() {
  apt-cache policy "$1" 2>/dev/null | sed -n 's/^ *Candidate: //p' | grep -v '(none)' |
    sed 's/^[0-9]*://; s/-[^-]*$//' || true
}
apt_install() {
  apt_update
  DEBIAN_FRONTEND=noninteractive "${sudo[@]}" apt-get install -y -q --no-install-recommends "$@"
}
cmake_version() { cmake --version 2>/dev/null | sed -n 's/^cmake version \([0-9.]*\).*/\1/p'; }

# CMake 3.25 or newer (the kit's presets need it). pip's CMake goes to /usr/local/bin, ahead of
# apt's in PATH; CMake 4 is left out, as it refuses the old find modules some packages still ship.
if ! at_least "$(cmake_version)" 3.25; then
  apt_update
  apt_cmake=$(apt_version cmake)
  if ! at_least "$apt_cmake" 3.25; then
    say "apt's CMake here is ${apt_cmake:-missing} (Ubuntu 22.04 has 3.22); springlab needs 3.25 or newer: installing CMake 3.x from PyPI with pip"
    apt_install python3-pip
    PIP_BREAK_SYSTEM_PACKAGES=1 "${sudo[@]}" python3 -m pip install -q 'cmake>=3.25,<4'
    hash -r
    at_least "$(cmake_version)" 3.25 ||
      die "CMake from pip is '$(cmake_version)' at $(command -v cmake || echo nowhere): springlab needs 3.25 or newer"
    say "CMake $(cmake_version) at $(command -v cmake)"
  fi
fi

# toml++ (Ubuntu 22.04 has no libtomlplusplus-dev): ./lab setup says so, and the kit's CMake then
# downloads its 3.4.0 release, pinned by its hash (Gradescope's image build has the network).
skip=""
# mold, the fast linker, only saves build time: left out where apt has none.
installed mold || { apt_update; [ -n "$(apt_version mold)" ] || skip="$skip mold"; }

say "Installing what the kit needs (./lab setup)"
SPRINGLAB_SKIP_PACKAGES=$skip "$KIT/lab" setup

# GCC 12 or newer (C++20 as the kit uses it); the build below uses $CXX when it is set.
gcc_version=$(g++ -dumpfullversion 2>/dev/null || g++ -dumpversion)
if ! at_least "$gcc_version" 12; then
  say "g++ here is $gcc_version (Ubuntu 22.04 has 11); springlab needs GCC 12: installing g++-12 and building with it"
  apt_install g++-12
  export CXX=g++-12
fi

cd "$KIT"
say "Building the grader (the kit, its tests and the reference, once: minutes; the steps done and"
say "the time left are shown), then each task's points"
"$KIT/lab" points

# The reference's time per test, measured once here and cached (calibration.txt), by grading the
# starter code once: springlab-grade measures it first, and stops with status 1 if the kit's own
# solutions fail a test, so a broken kit fails the image's build, not the students' submissions.
say "Measuring the reference's time per test (grading the starter code once)"
scratch=$(mktemp -d)
trap 'rm -rf "$scratch"' EXIT
if ! build/dev/tests/grader/springlab-grade --out "$scratch/results" --work "$scratch/work" \
  tasks >"$scratch/grade.log" 2> >(tee -a "$scratch/grade.log" | grep --line-buffered measur); then
  cat "$scratch/grade.log"
  die "springlab-grade failed on the starter code (above): the kit is broken, nothing could be graded"
fi
[ -s build/dev/tests/grader/calibration.txt ] ||
  die "springlab-grade wrote no build/dev/tests/grader/calibration.txt"

# run_autograder grades as nobody: it reads the kit and its build whatever this build's umask
# was, and never the solutions, the mutated solutions or the hidden tests (their sources are not
# needed once built and calibrated). So code under test cannot print them into its feedback even
# where the kernel lacks Landlock, which would confine it.
chmod -R a+rX .
for secret in solutions tests/mutants tests/hidden; do
  if [ -e "$secret" ]; then chmod -R go= "$secret"; fi
done
say "Hid solutions/, tests/mutants/ and tests/hidden/ (where present) from other users"
say "Ready in $(($(date +%s) - started)) s: run_autograder grades \$AUTOGRADER_ROOT/submission"
