#pragma once
// How a corrected coordinate is written back: in the style of the number it
// replaces. A number keeps at least its own decimal places and gets up to
// `max_decimals` (default 4 in mm, 5 in inch programs: 0.1 µm and 0.25 µm)
// so that a sub-µm correction is not rounded away; trailing zeros beyond
// the word's own decimals are dropped; a leading zero is left out when the
// original number had none (".5").
#include <string>
#include <string_view>

namespace abbe::compensate {

struct NumberStyle {
  int decimals = 0;           // decimal places of the original number
  bool leading_zero = true;   // "0.5" rather than ".5"
  bool plus_sign = false;     // "+1.0"
  bool point_always = false;  // "5." rather than "5" (Fanuc reads "5" as 5 increments)
};

NumberStyle number_style(std::string_view text);

// `value` rounded to `max_decimals` (≥ style.decimals) in the given style.
std::string format_number(double value, const NumberStyle& style, int max_decimals);
// The same appended to `out`.
void append_number(std::string& out, double value, const NumberStyle& style, int max_decimals);

// `value` rounded to `decimals` places (the number the text above represents).
double round_to(double value, int decimals);

}  // namespace abbe::compensate
