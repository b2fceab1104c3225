#pragma once
// The small program of the predict report tests: a rectangle at z = -280
// with G43 H1 (200 mm), 5 mm steps, 300 × 200 mm, after one rapid.
namespace abbe::test {

inline const char* kRectProgram =
    "G17 G21 G90 G94\n"
    "G43 H1\n"
    "G0 X-350 Y-150 Z-270\n"
    "G1 Z-280 F300\n"
    "G1 X-650 F1000\n"
    "G1 Y-350\n"
    "G1 X-350\n"
    "G1 Y-150\n"
    "M30\n";

}  // namespace abbe::test
