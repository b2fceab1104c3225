#!/usr/bin/env bash
# Front-end benchmark (DESIGN protocol: like with like, same file, best of 3).
#
# Builds abbe in Release ($ABBE_BENCH_BUILD, default build/release),
# generates programs of 10 k, 100 k and 1 M blocks with gen_program, and on
# each file runs, best of 3:
#   abbe interpret F                 interpret only, summary output
#   rs274 -t tbl -v var -g F         LinuxCNC's standalone interpreter (canonical calls to /dev/null)
#   abbe path F --count              interpret + fragment (5 mm), only a count
#   abbe path F -o /dev/null         the full path CSV
#   wc -l F
# and prints wall-clock seconds (and CPU user+sys), the ratios and the peak
# RSS (/usr/bin/time -f %M) of `abbe path` at each size.
#
# rs274 comes from the Debian package linuxcnc-uspace, unpacked (not
# installed) by `tools/install-deps.sh --test` into $ABBE_LINUXCNC_DIR
# (default /opt/abbe/linuxcnc). Without it the rs274 column says n/a.
#
# usage: tools/benchmark.sh [SIZES...]   (default: 10000 100000 1000000)
# env:   ABBE_BENCH_DIR (default build/bench), ABBE_BENCH_REPEAT (default 3),
#        ABBE_BENCH_BUILD (Release build directory, default build/release)
set -euo pipefail
cd "$(dirname "$0")/.."
root=$(pwd)
sizes=("$@")
[ ${#sizes[@]} -gt 0 ] || sizes=(10000 100000 1000000)
work=${ABBE_BENCH_DIR:-$root/build/bench}
repeat=${ABBE_BENCH_REPEAT:-3}
mkdir -p "$work"

build=${ABBE_BENCH_BUILD:-$root/build/release}
echo "== building Release ($build, -j2)"
cmake -S . -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Release -DABBE_BUILD_GENERATORS=ON >/dev/null
cmake --build "$build" -j2 --target abbe gen_program >/dev/null
abbe=$build/abbe
gen=$build/gen_program

# ---- rs274 ----
rs274=""
lcnc=""
for d in "${ABBE_LINUXCNC_DIR:-/opt/abbe/linuxcnc}"; do
  if [ -n "$d" ] && [ -x "$d/usr/bin/rs274" ]; then lcnc=$d; break; fi
done
if [ -z "$lcnc" ]; then
  echo "   (no rs274: tools/install-deps.sh --test unpacks it; rs274 columns are n/a)"
fi
if [ -n "$lcnc" ]; then
  rs274=$lcnc/usr/bin/rs274
  export LD_LIBRARY_PATH="$lcnc/usr/lib${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}"
  printf 'T1 P1 Z0.1 D0.1 ;tool 1\n' >"$work/tools.tbl"
fi

has_interpret=1
"$abbe" interpret --help >/dev/null 2>&1 || has_interpret=0

# best_of CMD...: runs the command $repeat times (stdout to /dev/null) and
# prints "wall cpu maxrss_kb" of the run with the least CPU time (user + sys;
# on a shared machine the wall clock mostly measures waiting for a core;
# bash's time, ms resolution; peak RSS from /usr/bin/time -f %M).
best_of() {
  local best="" line t
  for _ in $(seq "$repeat"); do
    [ -n "$rs274" ] && : >"$work/rs274.var"
    t=$( { TIMEFORMAT='%3R %3U %3S'; time /usr/bin/time -f %M -o "$work/rss.txt" "$@" \
             >/dev/null 2>"$work/stderr.txt"; } 2>&1 ) || {
      echo "FAILED: $*" >&2
      cat "$work/stderr.txt" >&2
      return 1
    }
    line=$(echo "$t $(tail -1 "$work/rss.txt")" | awk '{printf "%.3f %.3f %d", $1, $2 + $3, $4}')
    # Compare the second fields (CPU time).
    if [ -z "$best" ] || awk -v a="$line" -v b="$best" 'BEGIN{split(a, x); split(b, y); exit !(x[2] < y[2])}'; then
      best=$line
    fi
  done
  echo "$best"
}
ratio() { awk -v a="$1" -v b="$2" 'BEGIN{ if (a == "n/a" || b == "n/a" || b <= 0) print "n/a"; else printf "%.1f", a / b }'; }

printf '\n== %s, %s, nproc %s, load %s\n' "$(date -u +%Y-%m-%dT%H:%MZ)" "$(uname -m)" "$(nproc)" \
  "$(cut -d' ' -f1-3 /proc/loadavg)"
summary=()
for n in "${sizes[@]}"; do
  f=$work/gen_${n}.ngc
  [ -s "$f" ] || "$gen" --blocks "$n" --seed 1 -o "$f"
  bytes=$(stat -c %s "$f")
  lines=$(wc -l <"$f")
  points=$("$abbe" path "$f" --count | sed -n 's/.*points=\([0-9]*\).*/\1/p')
  echo
  echo "-- $n blocks: $f, $bytes bytes, $lines lines, $points points at 5 mm"
  if [ $has_interpret = 1 ]; then interp=$(best_of "$abbe" interpret "$f"); else interp="n/a n/a 0"; fi
  if [ -n "$rs274" ]; then rs=$(best_of "$rs274" -t "$work/tools.tbl" -v "$work/rs274.var" -g "$f"); else rs="n/a n/a 0"; fi
  count=$(best_of "$abbe" path "$f" --count)
  full=$(best_of "$abbe" path "$f" -o /dev/null)
  wcl=$(best_of wc -l "$f")
  printf '   %-34s %9s %9s %10s\n' "command (best of $repeat)" "wall s" "cpu s" "peak RSS"
  printf '   %-34s %9s %9s %8s KB\n' "abbe interpret" $interp
  printf '   %-34s %9s %9s %8s KB\n' "rs274 -g" $rs
  printf '   %-34s %9s %9s %8s KB\n' "abbe path --count (fragment 5 mm)" $count
  printf '   %-34s %9s %9s %8s KB\n' "abbe path -o /dev/null (CSV)" $full
  printf '   %-34s %9s %9s %8s KB\n' "wc -l" $wcl
  w() { echo "$1" | cut -d' ' -f1; }
  c() { echo "$1" | cut -d' ' -f2; }
  echo "   ratios (wall; cpu):"
  echo "     rs274 / abbe interpret            $(ratio "$(w "$rs")" "$(w "$interp")"); $(ratio "$(c "$rs")" "$(c "$interp")")   (headline: like with like)"
  echo "     rs274 / abbe path --count         $(ratio "$(w "$rs")" "$(w "$count")"); $(ratio "$(c "$rs")" "$(c "$count")")"
  echo "     abbe interpret / wc -l            $(ratio "$(w "$interp")" "$(w "$wcl")"); $(ratio "$(c "$interp")" "$(c "$wcl")")"
  echo "     abbe path CSV / wc -l             $(ratio "$(w "$full")" "$(w "$wcl")"); $(ratio "$(c "$full")" "$(c "$wcl")")"
  summary+=("$n $(echo "$full" | cut -d' ' -f3)")
done

echo
echo "-- peak RSS of abbe path (CSV to /dev/null)"
base=""
for s in "${summary[@]}"; do
  set -- $s
  [ -n "$base" ] || base=$2
  echo "   $1 blocks: $2 KB ($(ratio "$2" "$base") x the smallest)"
done
