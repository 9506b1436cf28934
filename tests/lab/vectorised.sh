#!/usr/bin/env bash
# The fast paths are written for GCC's vectoriser (common/CMakeLists.txt): each of these objects
# must hold AVX2 code (256-bit registers) in its clones. A build setting that quietly takes -O3
# away (a precompiled header did, and every figure of the benchmarks fell with it) fails here.
set -euo pipefail
status=0
for name in grid_forces wind_velocities xpbd; do
  object=
  for candidate in "$@"; do
    case "$candidate" in */src/$name.cpp.o | */src/*/$name.cpp.o) object=$candidate ;; esac
  done
  [ -n "$object" ] || { echo "no object for $name.cpp among the libraries'"; status=1; continue; }
  count=$(objdump -d --no-show-raw-insn "$object" | grep -c 'ymm' || true)
  echo "$name.cpp.o: $count instructions on 256-bit registers"
  [ "$count" -gt 0 ] || { echo "$name.cpp was not vectorised for AVX2"; status=1; }
done
exit "$status"
