#!/usr/bin/env bash
# The portable path's speed against the AVX2 one (issue 36), side by side in one run: the same
# benchmark program built twice, by the release preset (AVX2 clones chosen at load time) and by
# release-portable (-DSPRINGLAB_PORTABLE_ONLY: the baseline loops only, as arm64, macOS and
# Windows build them), run in alternation, ROUNDS times each, on the rows of the fast force path
# and of XPBD. Prints each row's least time of each build and their ratio.
#   tests/benchmarks/portable.sh [ROUNDS]        (from the kit's folder; builds both first)
set -euo pipefail
rounds=${1:-3}
for preset in release release-portable; do
  [ -f "build/$preset/build.ninja" ] || cmake --preset "$preset" >/dev/null
  cmake --build "build/$preset" --target springlab-bench >/dev/null
done
scratch=$(mktemp -d)
trap 'rm -rf "$scratch"' EXIT
rows="force/fast/100 force/fast/300 force/model+wind/100 force/model+wind/300 step/xpbd/100 step/xpbd/300"
# One row per run: Google Benchmark's CSV needs the same counters in every row of a run, and the
# rows count different things. The figure is ns_per_spring (force rows) or ns_per_projection
# (XPBD), read from the run's own header; "preset,row,figure" lines.
figure() {  # figure PRESET ROW
  "build/$1/tests/benchmarks/springlab-bench" --benchmark_filter="^${2//+/\\+}\$" \
    --benchmark_format=csv 2>/dev/null |
    awk -F, -v preset="$1" -v row="$2" '
      /^name,/ { for (i = 1; i <= NF; ++i) { gsub(/"/, "", $i); column[$i] = i }; next }
      /^"(force|step)\// { c = row ~ /^step\/xpbd/ ? column["ns_per_projection"] : column["ns_per_spring"]
                           print preset "," row "," $c }'
}
for _ in $(seq "$rounds"); do
  for row in $rows; do
    for preset in release release-portable; do
      figure "$preset" "$row" >>"$scratch/rows.csv"
    done
  done
done
echo "machine: $(grep -m 1 'model name' /proc/cpuinfo 2>/dev/null | cut -d: -f2 | sed 's/^ //'), load $(cut -d ' ' -f 1-3 /proc/loadavg 2>/dev/null); $(date -u '+%Y-%m-%d %H:%M UTC'); $rounds rounds, least of each"
printf "%-24s %12s %12s %8s\n" "row" "AVX2 ns" "portable ns" "ratio"
awk -F, '
  { key = $2 SUBSEP $1; v = $3 + 0
    if (!(key in best) || v < best[key]) best[key] = v; names[$2] = 1 }
  END { for (name in names) {
          a = best[name SUBSEP "release"]; p = best[name SUBSEP "release-portable"]
          printf "%-24s %12.3f %12.3f %8.2f\n", name, a, p, p / a } }' "$scratch/rows.csv" | sort
