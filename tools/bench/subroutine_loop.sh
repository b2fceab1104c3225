#!/usr/bin/env bash
# Writes the "subroutine in a loop" benchmark program of docs/performance.md
# (issue 13) to standard output: the given program (the 100 k-block file
# of gen_program) with an 11-block subroutine o<pass> at its top (its
# arguments in every coordinate, an arc) and, at its end, a loop that calls
# it N times (default 81800) with computed arguments.
# usage: tools/bench/subroutine_loop.sh PROGRAM [N] > out.ngc
set -euo pipefail
program=$1
repeats=${2:-81800}
cat <<'NGC'
o<pass> sub
  G0 Z[#3 + 5]
  G0 X[#1] Y[#2]
  G1 Z[#3] F[#4]
  G1 X[#1 + 10] Y[#2]
  G1 X[#1 + 10] Y[#2 + 10]
  G2 X[#1] Y[#2 + 10] I-5 J0
  G1 X[#1] Y[#2]
  G1 Z[#3 + 1]
  G1 X[#1 + 5] Y[#2 + 5]
  G0 Z[#3 + 5]
o<pass> endsub
NGC
cat "$program"
cat <<NGC
G17 G90 G94
#<i> = 0
o100 repeat [$repeats]
  o<pass> call [-500 + [#<i> MOD 100]] [-250 + [#<i> MOD 50]] [-300 - [#<i> MOD 7]] [800 + [#<i> MOD 5] * 100]
  #<i> = [#<i> + 1]
o100 endrepeat
M2
NGC
