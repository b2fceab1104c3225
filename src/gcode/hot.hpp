#pragma once
// ABBE_HOT marks a function on the per-block path of every program: read,
// parse, classify, plan, convert, deliver. GCC places such functions
// together (.text.hot), so that the loop over a program's blocks stays in
// the instruction cache next to the caller's own per-point work (path,
// predict). Measured with cachegrind, `abbe path --count` on 100 k blocks:
// see docs/performance.md.
#if defined(__GNUC__)
#define ABBE_HOT [[gnu::hot]]
#else
#define ABBE_HOT
#endif
