#pragma once
// The fixed-point number text of every file abbe writes: a value rounded to
// 6 decimals (half away from zero), trailing zeros and a bare '.' dropped —
// 1.5 → "1.5", -350 → "-350", 1e-7 → "0".
//
// write_fixed6 is the in-place core for writers that format whole rows into
// memory they reserved (the path writer, predict's rows). It is defined here
// so that every writer shares one definition; the compiler keeps it out of
// line where a row holds many numbers (forcing it inline into predict's row
// made predict 30 % slower: docs/performance.md). fixed6_fits(v) says
// whether write_fixed6 can take v (finite, |v| < 9e12, so that v·1e6 fits an
// int64); other values go through io::append_fixed6 (path_writer.hpp), which
// writes the same text for the values both take and handles NaN, infinity
// and huge numbers.
#include <fmt/format.h>

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>

namespace abbe::io {

// Bytes write_fixed6 may store from `out` (at most 21 are text; the bytes past
// the returned end are scratch).
inline constexpr std::size_t kFixed6MaxChars = 24;

inline bool fixed6_fits(double value) {  // NaN: false; no branch
  return (value < 9e12) & (value > -9e12);
}

// Writes the decimal digits of v (at most 20) from `out`; returns one past the last.
char* write_decimal(char* out, unsigned long long v);

// Appends `value` in the same text, for any value: non-finite → "nan"/"inf",
// huge values with printf's "%.6f".
void append_fixed6(fmt::memory_buffer& out, double value);

namespace detail {
// "000" … "999" as 32-bit words (the first character in the lowest byte, the
// fourth byte zero): three digits per table lookup.
struct DigitTriples {
  std::uint32_t word[1000];
  constexpr DigitTriples() : word() {
    for (std::uint32_t i = 0; i < 1000; ++i)
      word[i] = (48 + i / 100) | (48 + i / 10 % 10) << 8 | (48 + i % 10) << 16;
  }
};
inline constexpr DigitTriples kDigitTriples{};
}  // namespace detail

// Requires fixed6_fits(value). Returns one past the last character written.
inline char* write_fixed6(char* p, double value) {
  const double scaled = value * 1e6;
  const long long r = static_cast<long long>(scaled + std::copysign(0.5, scaled));
  *p = '-';
  p += r < 0;
  const unsigned long long u =
      r < 0 ? 0ULL - static_cast<unsigned long long>(r) : static_cast<unsigned long long>(r);
  const unsigned long long int_part = u / 1000000ULL;
  const auto frac = static_cast<std::uint32_t>(u - int_part * 1000000ULL);
#if defined(__BYTE_ORDER__) && __BYTE_ORDER__ == __ORDER_BIG_ENDIAN__
  p = write_decimal(p, int_part);
  if (frac == 0) return p;
  p[0] = '.';
  std::uint32_t rest = frac;
  for (int i = 6; i >= 1; --i, rest /= 10) p[i] = static_cast<char>('0' + rest % 10);
  char* end = p + 7;
  while (end[-1] == '0') --end;
  return end;
#else
  // Little-endian: the digits are assembled in a register (the first
  // character in the lowest byte) and stored with one unaligned write; the
  // lengths are computed without branches (the digit counts of a column vary
  // from row to row, which a branch predictor cannot follow).
  if (int_part < 1000) {
    // Up to three digits: one lookup, the leading zeros shifted out.
    const auto v = static_cast<std::uint32_t>(int_part);
    const std::uint32_t n = 1u + (v >= 10) + (v >= 100);
    const std::uint32_t w = detail::kDigitTriples.word[v] >> (8 * (3 - n));
    std::memcpy(p, &w, 4);
    p += n;
  } else {
    p = write_decimal(p, int_part);
  }
  if (frac == 0) return p;
  // ".dddddd" and a zero byte in one store; keep the digits up to the last
  // nonzero one (trailing zeros dropped).
  const std::uint64_t digits = std::uint64_t{detail::kDigitTriples.word[frac / 1000]} |
                               std::uint64_t{detail::kDigitTriples.word[frac % 1000]} << 24;
  const std::uint64_t w = '.' | digits << 8;
  std::memcpy(p, &w, 8);
  const std::uint64_t values = digits ^ 0x303030303030ULL;  // digit values, nonzero: frac > 0
  const int last = (63 - __builtin_clzll(values)) / 8;      // byte of the last nonzero digit
  return p + 2 + last;
#endif
}

}  // namespace abbe::io
