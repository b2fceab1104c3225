#include "abbe/io/fixed6.hpp"

#include <iterator>
#include <string_view>

namespace abbe::io {

namespace {
// "00" "01" … "99": two digits per table lookup.
constexpr char kDigitPairs[] =
    "00010203040506070809101112131415161718192021222324252627282930313233343536373839"
    "40414243444546474849505152535455565758596061626364656667686970717273747576777879"
    "8081828384858687888990919293949596979899";

int count_digits(unsigned long long v) {
  int n = 1;
  for (;;) {
    if (v < 10) return n;
    if (v < 100) return n + 1;
    if (v < 1000) return n + 2;
    if (v < 10000) return n + 3;
    v /= 10000;
    n += 4;
  }
}
}  // namespace

char* write_decimal(char* out, unsigned long long v) {
  char* end = out + count_digits(v);
  char* p = end;
  // Backwards from the last digit, two at a time.
  while (v >= 100) {
    const auto pair = static_cast<std::size_t>(v % 100) * 2;
    v /= 100;
    p -= 2;
    std::memcpy(p, kDigitPairs + pair, 2);
  }
  if (v >= 10) {
    p -= 2;
    std::memcpy(p, kDigitPairs + static_cast<std::size_t>(v) * 2, 2);
  } else {
    *--p = static_cast<char>('0' + v);
  }
  return end;
}

void append_fixed6(fmt::memory_buffer& out, double value) {
  if (!std::isfinite(value)) {
    const std::string_view s = std::isnan(value) ? "nan" : (value > 0 ? "inf" : "-inf");
    out.append(s.data(), s.data() + s.size());
    return;
  }
  if (!fixed6_fits(value)) {
    fmt::format_to(std::back_inserter(out), "{:.6f}", value);
    return;
  }
  char digits[kFixed6MaxChars];
  out.append(digits, write_fixed6(digits, value));
}

}  // namespace abbe::io
