#!/usr/bin/env bash
# Interoperability test: abbe's interpreter against LinuxCNC's standalone
# rs274 (Debian package linuxcnc-uspace) on every .ngc file of that package's
# ncfiles directory and every file in nc-samples/.
#
# usage: run_interop.sh ABBE CANON_COMPARE WORK_DIR SOURCE_DIR [RANDOM_PROGRAMS
#                       [COMPENSATED_COMPARE GEN_PROGRAM [GEN_FLOW_PROGRAMS]]]
#
# With RANDOM_PROGRAMS (tests/interop/random_programs.cpp), also
# $ABBE_INTEROP_RANDOM (default 100) generated programs (fixed seeds) are
# compared, in the configuration of abbe's own programs.
#
# With COMPENSATED_COMPARE (tests/interop/compensated_compare.cpp) and
# GEN_PROGRAM (tools/gen), every nc-samples/ file and a generated program
# (2000 blocks) are compensated with the sample machine (`abbe compensate`),
# the compensated file goes through rs274 too, and each of its canonical
# end points must be the original's plus abbe's compensation vector there;
# every file abbe refuses must be refused by `abbe compensate` with the
# message `abbe interpret --machine` gives in the same configuration.
#
# With GEN_FLOW_PROGRAMS (tools/gen/gen_flow_programs.cpp), also
# $ABBE_INTEROP_FLOW (default 50) generated programs with parameters,
# expressions and O-word control flow (fixed seeds) are compared call by call.
#
# Each file is classified (see docs/interop.md): matched, refused (abbe
# stops with a clear file:line:col error; OK), rs274-refused (rs274 stops
# with an error, abbe does not; listed), or mismatch / abbe-failed (test
# failure). The counts and the per-file table go to stdout and to
# <work>/results.md; with ABBE_INTEROP_REPORT=<absolute path of docs/interop.md> (or another
# page with the result markers) they also replace that page's results.
#
# rs274 comes from `tools/install-deps.sh --test` ($ABBE_LINUXCNC_DIR,
# default /opt/abbe/linuxcnc). Without it the test fails loudly;
# ABBE_SKIP_INTEROP=1 skips it (exit 77, reported by ctest as skipped).
set -uo pipefail

if [ $# -ne 4 ] && [ $# -ne 5 ] && [ $# -ne 7 ] && [ $# -ne 8 ]; then
  echo "usage: $0 ABBE CANON_COMPARE WORK_DIR SOURCE_DIR [RANDOM_PROGRAMS [COMPENSATED_COMPARE GEN_PROGRAM [GEN_FLOW_PROGRAMS]]]" >&2
  exit 2
fi
abbe=$1
compare=$2
work=$3
src=$4
random_programs=${5:-}
comp_compare=${6:-}
gen_program=${7:-}
gen_flow=${8:-}
sample_machine="$src/machines/sample/machine.yaml"

if [ "${ABBE_SKIP_INTEROP:-0}" = "1" ]; then
  echo "interop: skipped (ABBE_SKIP_INTEROP=1)"
  exit 77
fi

fail() {
  echo "interop: FAILED: $*" >&2
  echo "interop: (set ABBE_SKIP_INTEROP=1 to skip this test on a machine without it)" >&2
  exit 1
}

mkdir -p "$work" || fail "cannot create $work"
# rs274 is put in place by `tools/install-deps.sh --test` (the package
# linuxcnc-uspace unpacked under $ABBE_LINUXCNC_DIR, default
# /opt/abbe/linuxcnc); this test downloads nothing.
lcnc=${ABBE_LINUXCNC_DIR:-/opt/abbe/linuxcnc}
rs274="$lcnc/usr/bin/rs274"
[ -x "$rs274" ] ||
  fail "no rs274 in $lcnc: run tools/install-deps.sh --test (it unpacks linuxcnc-uspace there)"
ncfiles="$lcnc/usr/share/linuxcnc/ncfiles"
[ -d "$ncfiles" ] || fail "no ncfiles directory in the unpacked package ($ncfiles)"
export LD_LIBRARY_PATH="$lcnc/usr/lib${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}"

# Two configurations, the same for rs274 and abbe:
# - LinuxCNC's ncfiles and nc-samples/: every tool 1..99 of length 0, all
#   work offsets 0. Zero lengths because the standalone rs274 re-reads its
#   position after a tool change (M6) from its dummy canonical layer, which
#   ignores tool length offsets: with non-zero lengths its program Z after
#   "M6 ... G43 Hn" differs from what a LinuxCNC machine (and abbe) does
#   (docs/interop.md).
# - tests/interop/ncfiles/ (abbe's own interop programs, no M6): tool n has
#   length n/10 inch and G54..G59 have non-zero offsets.
# rs274's tool table and parameter file are in inches; abbe gets mm.
tool_table() {  # file length_per_tool_number_inch
  : >"$1"
  for n in $(seq 1 99); do
    printf 'T%d P%d Z%s D0.1 ;tool %d\n' "$n" "$n" "$(awk -v n="$n" -v k="$2" 'BEGIN{printf "%.4f", n*k}')" "$n" >>"$1"
  done
}
tool_args() {  # length_per_tool_number_inch
  for n in $(seq 1 99); do
    printf -- '--tool\n%d=%s\n' "$n" "$(awk -v n="$n" -v k="$1" 'BEGIN{printf "%.6f", n*k*25.4}')"
    # The table's D0.1 (inch): the cutter diameter of G41/G42.
    printf -- '--tool-diameter\n%d=2.54\n' "$n"
  done
}
plain_table="$work/tools-zero.tbl"
tool_table "$plain_table" 0
mapfile -t plain_args < <(tool_args 0)
own_table="$work/tools-own.tbl"
tool_table "$own_table" 0.1
mapfile -t own_args < <(tool_args 0.1)
# G54..G59 (inch): parameters 5221.. in steps of 20.
own_offsets=("0.5 0.25 -1.0" "10 -5 2" "-3 4 0.5" "1 1 1" "-2 -2 -2" "0.125 0.375 -0.25")
own_var="$work/own.var.template"
: >"$own_var"
for k in 0 1 2 3 4 5; do
  read -r ox oy oz <<<"${own_offsets[$k]}"
  base=$((5221 + 20 * k))
  printf '%d\t%s\n%d\t%s\n%d\t%s\n' "$base" "$ox" $((base + 1)) "$oy" $((base + 2)) "$oz" >>"$own_var"
  own_args+=(--work-offset "G5$((4 + k))=$(awk -v x="$ox" -v y="$oy" -v z="$oz" 'BEGIN{printf "%.6f,%.6f,%.6f", x*25.4, y*25.4, z*25.4}')")
done

# rs274 keeps its tool table in a memory-mapped file, $HOME/.tool.mmap: two
# rs274 processes with one HOME (two interop runs of two build trees at
# once) corrupt each other's table (bus errors, tool lengths of 0). Each
# run gets a HOME of its own.
rs274_home="$work/rs274-home"
mkdir -p "$rs274_home"
run_rs274() {  # file out table var_template -> exit code
  local var="$work/rs274.var"
  if [ -n "${4:-}" ]; then cp "$4" "$var"; else : >"$var"; fi
  (cd "$(dirname "$1")" && HOME="$rs274_home" timeout 60 "$rs274" -t "$3" -v "$var" -g "$1" >"$2" 2>&1)
}

# rs274 must start at all (its runtime libraries, e.g. libboost-python).
smoke="$work/smoke.ngc"
printf 'G0 X1 Y2 Z3\nM2\n' >"$smoke"
run_rs274 "$smoke" "$work/smoke.out" "$plain_table"
grep -q "STRAIGHT_TRAVERSE(1.0000, 2.0000, 3.0000" "$work/smoke.out" ||
  fail "rs274 does not run: $(head -3 "$work/smoke.out") (tools/install-deps.sh installs its runtime)"

# The comparator must be able to fail: one motion off by 2e-4 mm must be a
# mismatch, a missing motion too, the exact one a match.
printf 'N1 STRAIGHT_TRAVERSE(1.000000, 2.000000, 3.000000) F=0.000000 TL=0.000000\n' >"$work/smoke.abbe"
printf 'N1 STRAIGHT_TRAVERSE(1.000200, 2.000000, 3.000000) F=0.000000 TL=0.000000\n' >"$work/smoke-off.abbe"
: >"$work/smoke.err"
: >"$work/smoke-none.abbe"
"$compare" "$work/smoke.out" 0 "$work/smoke.abbe" "$work/smoke.err" 0 >/dev/null ||
  fail "canon_compare rejects an exact match"
if "$compare" "$work/smoke.out" 0 "$work/smoke-off.abbe" "$work/smoke.err" 0 >/dev/null ||
  "$compare" "$work/smoke.out" 0 "$work/smoke-none.abbe" "$work/smoke.err" 0 >/dev/null; then
  fail "canon_compare accepts a wrong or missing motion"
fi

# add_found DIR FIND-TESTS…: the files below DIR that pass FIND-TESTS, sorted,
# onto files.
add_found() {
  local dir=$1 f
  shift
  while IFS= read -r f; do files+=("$f"); done < <(find "$dir" -type f "$@" | sort)
}
# add_written DIR WHAT COMMAND…: COMMAND… DIR writes programs into a fresh
# DIR; its .ngc files onto files.
add_written() {
  local dir=$1 what=$2
  shift 2
  rm -rf "$dir" && mkdir -p "$dir"
  "$@" "$dir" || fail "$what failed"
  add_found "$dir" -name '*.ngc'
}

files=()
add_found "$ncfiles" -name '*.ngc'
if [ -d "$src/nc-samples" ]; then
  add_found "$src/nc-samples"
fi
own_dir="$src/tests/interop/ncfiles"
add_found "$own_dir" -name '*.ngc'
# Real programs written by CAM software for 3-axis mills and routers
# (tests/data/cam-corpus/README.md names the source of each), plain tool table.
cam_dir="$src/tests/data/cam-corpus"
if [ -d "$cam_dir" ]; then
  add_found "$cam_dir" ! -name README.md
fi
random_dir="$work/random"
if [ -n "$random_programs" ]; then
  add_written "$random_dir" random_programs "$random_programs" "${ABBE_INTEROP_RANDOM:-100}"
fi
generated_dir="$work/generated"
if [ -n "$gen_program" ]; then
  rm -rf "$generated_dir" && mkdir -p "$generated_dir"
  "$gen_program" --blocks 2000 --seed 3 -o "$generated_dir/gen-2000.ngc" ||
    fail "gen_program failed"
  files+=("$generated_dir/gen-2000.ngc")
fi

flow_dir="$work/flow"
if [ -n "$gen_flow" ]; then
  add_written "$flow_dir" gen_flow_programs "$gen_flow" "${ABBE_INTEROP_FLOW:-50}"
fi

out="$work/out"
rm -rf "$out" && mkdir -p "$out"

# compensated_check FILE NAME CLASS INDEX TABLE VAR: the compensated program
# in rs274 (see the header). Results into $comp_rows; failures set status.
compensated_check() {
  local f=$1 name=$2 class=$3 i=$4 table=$5 var=$6 cclass detail rc
  # Compensated: nc-samples/ and the generated program; refusals: every file.
  case "$class:$name" in matched:nc-samples/* | matched:generated/* | refused:*) ;; *) return ;; esac
  local comp="$out/$i.comp.ngc"
  timeout 120 "$abbe" compensate "$f" --machine "$sample_machine" --allow-outside-travel -o "$comp" \
    >"$out/$i.comp.log" 2>"$out/$i.comp.err"
  rc=$?
  if [ "$class" = refused ]; then
    # The same first message line as `abbe interpret` in the same configuration
    # (the machine's tool table and offsets): file:line:col: error: …
    timeout 60 "$abbe" interpret --machine "$sample_machine" "$f" >/dev/null 2>"$out/$i.merr"
    # compensate rewrites line by line and refuses parameters, expressions
    # and O-words at their first line, by name: that refusal may come before
    # the construct interpret stops at. compensate also needs every tool's
    # length (interpret reads G43 Hn without one: the tip path does not
    # depend on it), so it may stop earlier at such a G43.
    if [ $rc = 1 ] && { [ "$(grep -m1 ': error: ' "$out/$i.comp.err")" = "$(grep -m1 ': error: ' "$out/$i.merr")" ] ||
      grep -q "not supported by a command that rewrites the program line by line\|has no length in the tool table" \
        "$out/$i.comp.err"; }; then
      ccount[still-refused]=$((${ccount[still-refused]} + 1))
    else
      ccount[mismatch]=$((${ccount[mismatch]} + 1))
      status=1
      detail="compensate exit $rc: $(head -1 "$out/$i.comp.err")"
      printf '%s\tmismatch\t0\t%s\n' "$name" "${detail//"$f"/$(basename "$f")}" >>"$comp_rows"
      echo "interop: compensated: $name refused by interpret but not so by compensate: $detail"
    fi
    return
  fi
  if [ $rc != 0 ]; then
    detail=$(head -1 "$out/$i.comp.err")
    detail=${detail//"$f"/$(basename "$f")}
    ccount[compensate-refused]=$((${ccount[compensate-refused]} + 1))
    printf '%s\tcompensate-refused\t0\t%s\n' "$name" "$detail" >>"$comp_rows"
    [ $rc = 1 ] || { status=1; echo "interop: compensated: $name: compensate exit $rc: $detail"; }
    return
  fi
  # (Files abbe matches call no subroutines: rs274 can read the copy in $out.)
  run_rs274 "$comp" "$out/$i.comp.rs274" "$table" "$var"
  local result
  result=$("$comp_compare" "$sample_machine" "$f" "$out/$i.rs274" "$out/$i.comp.rs274")
  rc=$?
  if [ $rc = 0 ] && [ "$name" = nc-samples/thesis-toolpath-1.ngc ]; then
    # The check must be able to fail: the last feed end moved by 1 µm (X).
    awk '{ a[NR] = $0 } /STRAIGHT_FEED\(/ { last = NR } END {
           for (k = 1; k <= NR; k++) {
             if (k == last) { split(a[k], p, "("); split(p[2], q, ",");
               sub(q[1] ",", sprintf("%.4f,", q[1] + 0.001), a[k]) }
             print a[k] } }' "$out/$i.comp.rs274" >"$out/$i.comp-off.rs274"
    if cmp -s "$out/$i.comp.rs274" "$out/$i.comp-off.rs274" ||
      "$comp_compare" "$sample_machine" "$f" "$out/$i.rs274" "$out/$i.comp-off.rs274" >/dev/null; then
      status=1
      echo "interop: compensated_compare accepts an end point 1 µm off ($name)"
    fi
  fi
  cclass=${result%%$'\t'*}
  ccount[$cclass]=$((${ccount[$cclass]:-0} + 1))
  printf '%s\t%s\n' "$name" "$result" >>"$comp_rows"
  if [ $rc -ne 0 ]; then
    status=1
    echo "interop: compensated: $cclass: $name: ${result#*$'\t'}"
  fi
}
rows="$work/rows.tsv"
: >"$rows"
comp_rows="$work/comp-rows.tsv"
: >"$comp_rows"
declare -A ccount=([matched]=0 [still-refused]=0 [compensate-refused]=0 [mismatch]=0)
declare -A count=([matched]=0 [refused]=0 [rs274-refused]=0 [mismatch]=0 [abbe-failed]=0)
status=0
i=0
for f in "${files[@]}"; do
  i=$((i + 1))
  table=$plain_table
  var=""
  args=("${plain_args[@]}")
  case "$f" in
    "$ncfiles"/*) name="ncfiles/${f#"$ncfiles"/}" ;;
    "$own_dir"/* | "$random_dir"/*)
      case "$f" in
        "$own_dir"/*) name="tests/interop/ncfiles/${f#"$own_dir"/}" ;;
        *) name="random/${f#"$random_dir"/}" ;;
      esac
      table=$own_table
      var=$own_var
      args=("${own_args[@]}")
      ;;
    "$generated_dir"/*) name="generated/${f#"$generated_dir"/}" ;;
    "$cam_dir"/*) name="cam-corpus/${f#"$cam_dir"/}" ;;
    "$flow_dir"/*) name="flow/${f#"$flow_dir"/}" ;;
    *) name="nc-samples/${f#"$src/nc-samples"/}" ;;
  esac
  run_rs274 "$f" "$out/$i.rs274" "$table" "$var"
  rs_exit=$?
  # rs274 runs in the file's folder and finds o<name> call's name.ngc there.
  timeout 60 "$abbe" interpret --canon "$f" "${args[@]}" --subroutine-path "$(dirname "$f")" \
    >"$out/$i.abbe" 2>"$out/$i.err"
  ab_exit=$?
  result=$("$compare" "$out/$i.rs274" "$rs_exit" "$out/$i.abbe" "$out/$i.err" "$ab_exit")
  cmp_exit=$?
  class=${result%%$'\t'*}
  rest=${result#*$'\t'}
  motions=${rest%%$'\t'*}
  detail=${rest#*$'\t'}
  # Error messages name the file by its full path; shorten to the table name.
  detail=${detail//"$f"/$(basename "$f")}
  count[$class]=$((${count[$class]:-0} + 1))
  printf '%s\t%s\t%s\t%s\n' "$name" "$class" "$motions" "$detail" >>"$rows"
  if [ $cmp_exit -ne 0 ]; then
    status=1
    echo "interop: $class: $name: $detail"
  fi
  # The public CAM corpus (issue 13): every program rs274 runs must be
  # accepted, except one with a rotary axis that moves or probing.
  if [ "$class" = refused ]; then
    case "$name:$detail" in
      cam-corpus/*"[rs274 refuses too:"* | cam-corpus/*"rotary axis "*" moves "* | cam-corpus/*"probing ("*) ;;
      cam-corpus/*)
        status=1
        echo "interop: cam-corpus: $name: rs274 runs it but abbe refuses it: $detail"
        ;;
    esac
  fi
  [ -n "$comp_compare" ] && compensated_check "$f" "$name" "$class" "$i" "$table" "$var"
done

total=${#files[@]}
summary="files=$total matched=${count[matched]} refused=${count[refused]} rs274-refused=${count[rs274-refused]} mismatched=${count[mismatch]} abbe-failed=${count[abbe-failed]}"
echo "interop: $summary"
column -t -s $'\t' "$rows" 2>/dev/null | cut -c1-200 || cat "$rows"
if [ -n "$comp_compare" ]; then
  csummary="matched=${ccount[matched]} still-refused=${ccount[still-refused]} compensate-refused=${ccount[compensate-refused]} mismatched=${ccount[mismatch]}"
  echo "interop: compensated programs: $csummary"
  column -t -s $'\t' "$comp_rows" 2>/dev/null | cut -c1-220 || cat "$comp_rows"
fi

# Report: replace the results section of docs/interop.md.
report=${ABBE_INTEROP_REPORT:-}
# The per-file table of a results file (name, class, motions, detail; tab-separated).
results_table() {
  echo "| file | result | motions | detail |"
  echo "|---|---|---|---|"
  while IFS=$'\t' read -r name class motions detail; do
    detail=${detail//|/\\|}
    echo "| $name | $class | $motions | $detail |"
  done <"$1"
}
version=$(cat "$lcnc/VERSION" 2>/dev/null)
{
  echo "<!-- interop-results-begin (written by tests/interop/run_interop.sh) -->"
  echo
  echo "Compared with rs274 from linuxcnc-uspace ${version:-unknown}."
  echo
  echo "| files | matched | refused by abbe | refused by rs274 only | mismatched | abbe failed |"
  echo "|---|---|---|---|---|---|"
  echo "| $total | ${count[matched]} | ${count[refused]} | ${count[rs274-refused]} | ${count[mismatch]} | ${count[abbe-failed]} |"
  echo
  results_table "$rows"
  echo
  if [ -n "$comp_compare" ]; then
    echo "Compensated programs (sample machine, ae-arm): rs274's end points against the"
    echo "original's plus abbe's compensation vectors."
    echo
    echo "| compensated and checked | refused as before | refused by compensate | mismatched |"
    echo "|---|---|---|---|"
    echo "| ${ccount[matched]} | ${ccount[still-refused]} | ${ccount[compensate-refused]} | ${ccount[mismatch]} |"
    echo
    results_table "$comp_rows"
    echo
  fi
  echo "<!-- interop-results-end -->"
} >"$work/results.md"
if [ -z "$report" ]; then
  echo "interop: results are in $work/results.md (ABBE_INTEROP_REPORT=/abs/path/docs/interop.md puts them into the docs)"
elif [ -f "$report" ] && grep -q 'interop-results-begin' "$report" && grep -q 'interop-results-end' "$report"; then
  tmp="$report.tmp.$$"
  awk -v results="$work/results.md" '
    /interop-results-begin/ { while ((getline line < results) > 0) print line; skip = 1; next }
    /interop-results-end/ { skip = 0; next }
    !skip { print }
  ' "$report" >"$tmp" && mv "$tmp" "$report"
  echo "interop: results written to $report"
else
  echo "interop: $report has no result markers; results are in $work/results.md"
fi
exit $status
