#!/usr/bin/env bash
# The portable path's speed against the AVX2 one (issue 36), side by side in one run: the same
# benchmark program built twice, by the release preset (AVX2 clones chosen at load time) and by
# release-portable (-DSPRINGLAB_PORTABLE_ONLY: the baseline loops only, as arm64, macOS and
# Windows build them), run in alternation, ROUNDS times each, on the rows of the fast force path
# and of XPBD. Prints each row's least time of each build and their ratio.
#   tests/benchmarks/portable.sh [ROUNDS]        (from the kit's folder; builds both first)
set -euo pipefail
rounds=${1:-3}
filter='^(force/fast|force/model\+wind|step/xpbd)/(100|300)$'
for preset in release release-portable; do
  [ -f "build/$preset/build.ninja" ] || cmake --preset "$preset" >/dev/null
  cmake --build "build/$preset" --target springlab-bench >/dev/null
done
scratch=$(mktemp -d)
trap 'rm -rf "$scratch"' EXIT
for round in $(seq "$rounds"); do
  for preset in release release-portable; do
    "build/$preset/tests/benchmarks/springlab-bench" --benchmark_filter="$filter" \
      --benchmark_format=csv 2>/dev/null | grep -E '^"(force|step)/' |
      sed "s/^/$preset,/" >>"$scratch/rows.csv"
  done
done
# Columns after the preset: name, iterations, real_time, cpu_time, ... the counters by header; the
# figure per row is ns_per_spring (force rows) or ns_per_projection (XPBD), least over rounds.
header=$("build/release/tests/benchmarks/springlab-bench" --benchmark_filter='^force/fast/10$' \
  --benchmark_format=csv 2>/dev/null | grep -m 1 '^name,')
echo "machine: $(grep -m 1 'model name' /proc/cpuinfo 2>/dev/null | cut -d: -f2 | sed 's/^ //'), load $(cut -d ' ' -f 1-3 /proc/loadavg 2>/dev/null); $(date -u '+%Y-%m-%d %H:%M UTC')"
awk -F, -v header="$header" '
  BEGIN { n = split(header, h, ","); for (i = 1; i <= n; ++i) column[h[i]] = i + 1 }
  { name = $2; gsub(/"/, "", name)
    c = name ~ /^step\/xpbd/ ? column["ns_per_projection"] : column["ns_per_spring"]
    v = $c + 0; key = name SUBSEP $1
    if (!(key in best) || v < best[key]) best[key] = v; names[name] = 1 }
  END { printf "%-24s %12s %12s %8s\n", "row", "AVX2 ns", "portable ns", "ratio"
        for (name in names) {
          a = best[name SUBSEP "release"]; p = best[name SUBSEP "release-portable"]
          printf "%-24s %12.3f %12.3f %8.2f\n", name, a, p, p / a } }' "$scratch/rows.csv" | sort
