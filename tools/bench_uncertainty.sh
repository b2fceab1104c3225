#!/usr/bin/env bash
# Whole-process benchmark of `abbe predict --uncertainty N` against plain
# `abbe predict` on the thesis toolpaths (nc-samples/thesis-toolpath-*.ngc),
# same binary, same run, best of $ABBE_BENCH_REPEAT (CPU time user + sys),
# and the ratio; also `--uncertainty N --align best-fit` (every draw's part
# set up again). Machine: machines/sample/machine-uncertainty.yaml.
#
# usage: tools/bench_uncertainty.sh [ABBE] [N]
#   ABBE: the abbe executable (default build/release/abbe, else build/test/abbe)
#   N:    Monte Carlo draws (default 200)
# env:    ABBE_BENCH_REPEAT (default 3)
set -euo pipefail
cd "$(dirname "$0")/.."
abbe=${1:-}
if [ -z "$abbe" ]; then
  abbe=build/release/abbe
  [ -x "$abbe" ] || abbe=build/test/abbe
fi
draws=${2:-200}
repeat=${ABBE_BENCH_REPEAT:-3}
machine=machines/sample/machine-uncertainty.yaml
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

# best CMD...: the least CPU time (user + sys, s) of $repeat runs.
best() {
  local b=""
  for _ in $(seq "$repeat"); do
    local t
    t=$( { TIMEFORMAT='%3U %3S'; time "$@" >/dev/null 2>&1; } 2>&1 )
    t=$(awk '{printf "%.3f", $1 + $2}' <<<"$t")
    if [ -z "$b" ] || awk -v a="$t" -v b="$b" 'BEGIN{exit !(a < b)}'; then b=$t; fi
  done
  echo "$b"
}

echo "abbe: $abbe; draws: $draws; best of $repeat (CPU s)"
printf '%-22s %-7s %7s %9s %12s %8s %12s %8s\n' program model points plain "uncertainty" ratio \
  "+align" ratio
for p in nc-samples/thesis-toolpath-1.ngc nc-samples/thesis-toolpath-2.ngc; do
  for m in ae-arm all; do
    points=$("$abbe" -q predict "$p" --machine "$machine" --model "$m" -o - 2>/dev/null | tail -n +2 | wc -l)
    a=$(best "$abbe" -q predict "$p" --machine "$machine" --model "$m" -o "$tmp/plain.csv")
    b=$(best "$abbe" -q predict "$p" --machine "$machine" --model "$m" --uncertainty "$draws" \
      -o "$tmp/u.csv")
    c=$(best "$abbe" -q predict "$p" --machine "$machine" --model "$m" --uncertainty "$draws" \
      --align best-fit -o "$tmp/ua.csv")
    ratio() { awk -v a="$1" -v b="$2" 'BEGIN{ if (a > 0) printf "%.1f", b / a; else print "n/a" }'; }
    printf '%-22s %-7s %7s %9s %12s %8s %12s %8s\n' "$(basename "$p")" "$m" "$points" "$a" "$b" \
      "$(ratio "$a" "$b")" "$c" "$(ratio "$a" "$c")"
  done
done
