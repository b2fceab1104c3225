#!/usr/bin/env bash
# Runs the hidden-effect harness (tests/unit/diagnose_designs_test.cpp) over
# many seeds and prints its rate lines and the cases that went wrong or
# were missed, for docs/diagnosis.md's tables.
#
#   tools/sweep_designs.sh [-b build-dir] [-n seeds] [-j jobs] [-o out-dir] TEST...
#
# TEST is a DiagnoseDesigns test name (Grid, Plane, Toolpath, Ballbar,
# Diagonals, DiagonalsFiveRuns, AxisLines, GridOnePass, GridWithoutDirectionsInferred,
# GridIrregular, BallbarXY, GridTwoEffects, GridWithOutliers), or `all`.
# The harness's own variables pass through the environment:
#   ABBE_DESIGNS_VM_SEED / _PROFILE / _CHAIN  another truth machine
#   ABBE_DESIGNS_GRID=NXxNYxNZ                the grid's levels (e.g. 6x6x6)
#   ABBE_DESIGNS_DT_SCALE=f                   time per point × f
#   ABBE_DESIGNS_NOISE=µm                     another measurement noise (0.5)
#   ABBE_DESIGNS_BALLBAR_RADIUS=mm            another ballbar length (150)
#   ABBE_DESIGNS_DIAGONAL_STEP=mm             another target spacing on the diagonals (37)
#   ABBE_DESIGNS_PLATE_PITCH=mm               another hole pitch of the plate (50)
# One case with the diagnosis's selection log:
#   ABBE_DIAGNOSE_CASE=i build/rt/tests/abbe_tests --gtest_filter=DiagnoseDesigns.Grid
set -euo pipefail

build=build/rt
seeds=200
jobs=2
out=
while getopts "b:n:j:o:" opt; do
  case "$opt" in
    b) build=$OPTARG ;;
    n) seeds=$OPTARG ;;
    j) jobs=$OPTARG ;;
    o) out=$OPTARG ;;
    *) sed -n '2,20p' "$0" >&2; exit 1 ;;
  esac
done
shift $((OPTIND - 1))
if [[ $# -eq 0 ]]; then
  sed -n '2,20p' "$0" >&2
  exit 1
fi
tests=("$@")
if [[ ${tests[0]} == all ]]; then
  tests=(Grid Plane Toolpath Ballbar Diagonals DiagonalsFiveRuns AxisLines GridOnePass GridWithoutDirectionsInferred
         GridIrregular BallbarXY GridTwoEffects GridWithOutliers)
fi
binary=$build/tests/abbe_tests
if [[ ! -x $binary ]]; then
  echo "sweep_designs: $binary not found (build with -DABBE_BUILD_TESTS=ON)" >&2
  exit 1
fi
out=${out:-$(mktemp -d)}
mkdir -p "$out"

run_one() {
  ABBE_DIAGNOSE_SEEDS=$seeds "$binary" --gtest_filter="DiagnoseDesigns.$1" > "$out/$1.log" 2>&1 || true
}
export -f run_one
export binary seeds out
printf '%s\n' "${tests[@]}" | xargs -P "$jobs" -I{} bash -c 'run_one {}'

for t in "${tests[@]}"; do
  echo "== $t ($seeds seeds, $out/$t.log)"
  grep -E "^(RATES|POWER|TWO|OUTLIERS)" "$out/$t.log" || true
  grep -E "WRONG|missed|NAMED|\| (one|none) \|" "$out/$t.log" | cut -c1-220 || true
done
