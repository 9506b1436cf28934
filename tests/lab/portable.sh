#!/usr/bin/env bash
# The AVX2 paths and the portable one give the same bits (issue 36): the runner natively (AVX2 on
# this processor) against the same program under qemu-user emulating a processor without AVX2
# (Nehalem), which makes the loader pick every loop's baseline clone and XPBD's chunked
# projection, the path of arm64, macOS and Windows. Fabric scenes with the fast force path,
# gravity, pins and XPBD: every value the same bits. The one exception is the wind's gusts, whose
# sines come from glibc's vector library, 4 lanes on AVX2 and 2 without: there the fabric's
# positions after 1 s must agree to 1e-9 m, the rounding of a sine (a few ulp of the gust speed)
# carried through the motion.
#   tests/lab/portable.sh RUNNER
set -euo pipefail
runner=$1
scratch=$(mktemp -d)
trap 'rm -rf "$scratch"' EXIT
command -v qemu-x86_64 >/dev/null || { echo "qemu-x86_64 is not installed (./lab setup installs qemu-user)"; exit 1; }
grep -qw avx2 /proc/cpuinfo || { echo "this processor has no AVX2: nothing to compare"; exit 1; }
status=0
compare() {  # compare NAME TOLERANCE ARGS...
  local name=$1 tolerance=$2
  shift 2
  "$runner" --quiet --duration 1 --csv "$scratch/native.csv" "$@"
  qemu-x86_64 -cpu Nehalem "$runner" --quiet --duration 1 --csv "$scratch/portable.csv" "$@"
  local verdict
  if verdict=$("$(dirname "$0")/../../.ci/platforms/csv-close" "$scratch/native.csv" \
    "$scratch/portable.csv" "$tolerance"); then
    echo "$name: $verdict"
  else
    echo "$name: the portable path differs from AVX2's: $verdict"
    status=1
  fi
}
fabric=(--scene task5 --set rows=24 --set cols=24 --set wind.enabled=false)
compare "fabric, fast forces" 0 "${fabric[@]}"
compare "fabric, XPBD" 0 "${fabric[@]}" --integrator xpbd
compare "fabric, RK4" 0 "${fabric[@]}" --integrator rk4
compare "fabric in the wind" 1e-9 --scene task5 --set rows=24 --set cols=24
exit "$status"
