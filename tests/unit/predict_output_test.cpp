// The in-place fixed-point formatter `abbe predict` writes its rows with
// (io::write_fixed6, shared with the path writer): the same text as
// append_fixed6 and as printf("%.6f") with the trailing zeros dropped, for
// the magnitudes of coordinates (mm) and deviations (µm), the digit-count
// and rounding boundaries, and random values.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <limits>
#include <random>
#include <string>

#include "abbe/pipeline/path_writer.hpp"

namespace abbe::io {
namespace {

std::string in_place(double v) {
  std::array<char, kFixed6MaxChars + 8> buf;
  buf.fill('#');
  char* end = write_fixed6(buf.data(), v);
  EXPECT_LE(static_cast<std::size_t>(end - buf.data()), std::size_t{21}) << v;
  // Nothing is stored past kFixed6MaxChars.
  for (std::size_t i = kFixed6MaxChars; i < buf.size(); ++i) EXPECT_EQ(buf[i], '#') << v;
  return std::string(buf.data(), static_cast<std::size_t>(end - buf.data()));
}

std::string appended(double v) {
  fmt::memory_buffer b;
  append_fixed6(b, v);
  return fmt::to_string(b);
}

// printf's rounding, trailing zeros and a bare '.' dropped, "-0" → "0".
std::string printf6(double v) {
  char text[64];
  std::snprintf(text, sizeof text, "%.6f", v);
  std::string s(text);
  while (s.back() == '0') s.pop_back();
  if (s.back() == '.') s.pop_back();
  if (s == "-0") s = "0";
  return s;
}

TEST(PredictOutput, Fixed6InPlaceBoundaries) {
  const double values[] = {0.0,
                           -0.0,
                           1e-7,
                           -1e-7,
                           5e-7,
                           -5.1e-7,
                           0.000001,
                           -0.000001,
                           0.1,
                           -0.25,
                           1.5,
                           9.9999996,
                           9.999999,
                           10.0,
                           99.9999995,
                           100.0,
                           -999.9999996,
                           999.999999,
                           1000.0,
                           -1000.5,
                           9999.25,
                           10000.0,
                           123456.789,
                           -8.5e12,
                           8.99e12,
                           -350.0,
                           -299.99772,
                           2.28,
                           100000000008.0,
                           0.000123};
  for (double v : values) {
    ASSERT_TRUE(fixed6_fits(v)) << v;
    EXPECT_EQ(in_place(v), appended(v)) << v;
  }
  EXPECT_EQ(in_place(0.0), "0");
  EXPECT_EQ(in_place(-0.25), "-0.25");
  EXPECT_EQ(in_place(1e-7), "0");
  EXPECT_EQ(in_place(-5.1e-7), "-0.000001");
  EXPECT_EQ(in_place(9.9999996), "10");
  EXPECT_EQ(in_place(-999.9999996), "-1000");
  EXPECT_EQ(in_place(0.000123), "0.000123");
  EXPECT_EQ(in_place(123456.789), "123456.789");
  EXPECT_FALSE(fixed6_fits(9e12));
  EXPECT_FALSE(fixed6_fits(-1e300));
  EXPECT_FALSE(fixed6_fits(std::numeric_limits<double>::quiet_NaN()));
  EXPECT_FALSE(fixed6_fits(std::numeric_limits<double>::infinity()));
}

TEST(PredictOutput, Fixed6InPlaceMatchesPrintf) {
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> mm(-1200.0, 1200.0), um(-60.0, 60.0), big(-1e7, 1e7);
  for (int i = 0; i < 200000; ++i) {
    for (double v : {mm(rng), um(rng), big(rng), um(rng) * 1e-4}) {
      const std::string s = in_place(v);
      ASSERT_EQ(s, appended(v)) << v;
      // printf rounds the exact binary value; the formatter rounds v·1e6, so
      // the two may differ only at (near-)ties in the 7th decimal.
      if (s != printf6(v)) {
        const double scaled = std::abs(v) * 1e6;
        EXPECT_NEAR(scaled - std::floor(scaled), 0.5, 1e-6) << v << " " << s << " " << printf6(v);
      }
    }
  }
}

TEST(PredictOutput, DecimalIntegers) {
  for (unsigned long long v :
       {0ULL, 7ULL, 10ULL, 99ULL, 100ULL, 12345ULL, 18446744073709551615ULL}) {
    char buf[24];
    char* end = write_decimal(buf, v);
    EXPECT_EQ(std::string(buf, static_cast<std::size_t>(end - buf)), std::to_string(v));
  }
}

}  // namespace
}  // namespace abbe::io
