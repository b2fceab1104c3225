#!/usr/bin/env bash
# Builds the libFuzzer target fuzz_program with clang in its own build
# directory and runs it on the seed corpus (tests/fuzz/corpus) for a while.
# Fails (non-zero) on any crash, sanitizer report or escaped exception; the
# input that caused it is kept in <build dir>/artifacts/. See docs/fuzzing.md.
#
# Usage: run_fuzz.sh <source dir> <build dir> [seconds=60] [extra libFuzzer options...]
# Environment: ABBE_FUZZ_CXX (default clang++), ABBE_FUZZ_JOBS (build jobs, default 2).
# Exit code 77: clang++ or libFuzzer is not available (ctest reports a skip).
set -euo pipefail
src=$(cd "$1" && pwd)
build=$2
seconds=${3:-60}
shift $(( $# >= 3 ? 3 : $# ))
cxx=${ABBE_FUZZ_CXX:-clang++}

if ! command -v "$cxx" >/dev/null 2>&1; then
  echo "run_fuzz.sh: $cxx not found; skipping" >&2
  exit 77
fi
probe=$(mktemp -d)
trap 'rm -rf "$probe"' EXIT
printf '#include <cstddef>\n#include <cstdint>\nextern "C" int LLVMFuzzerTestOneInput(const std::uint8_t*, std::size_t) { return 0; }\n' \
  > "$probe/probe.cpp"
if ! "$cxx" -fsanitize=fuzzer "$probe/probe.cpp" -o "$probe/probe" 2>/dev/null; then
  echo "run_fuzz.sh: $cxx cannot link libFuzzer (-fsanitize=fuzzer); skipping" >&2
  exit 77
fi

# -O1 -g: what libFuzzer recommends, and it compiles faster than -O2.
cmake -S "$src" -B "$build" -G Ninja -DCMAKE_CXX_COMPILER="$cxx" -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -g" -DABBE_FUZZ=ON -DABBE_BUILD_TESTS=OFF -DABBE_BUILD_BENCHMARKS=OFF >/dev/null
cmake --build "$build" --target fuzz_program --parallel "${ABBE_FUZZ_JOBS:-2}"

# New inputs go to a scratch directory; the committed seeds are only read.
work="$probe/corpus"
mkdir -p "$work" "$build/artifacts"
export ASAN_OPTIONS=${ASAN_OPTIONS:-detect_leaks=1}
export UBSAN_OPTIONS=${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1}
"$build/fuzz_program" -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 -max_len=4096 \
  -dict="$src/tests/fuzz/gcode.dict" -artifact_prefix="$build/artifacts/" -print_final_stats=1 \
  "$@" "$work" "$src/tests/fuzz/corpus"
