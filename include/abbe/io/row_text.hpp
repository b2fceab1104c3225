#pragma once
// The text of one output row, written through one of two sinks with the same
// calls, so that a writer formats a row once, as a template over the sink:
//  - InPlaceRow writes into memory reserved for the whole row (every number
//    must satisfy fixed6_fits): no call per literal, no allocation;
//  - AppendedRow appends to a buffer and takes any number (append_fixed6).
// Both write the same text for the same calls (the path writer and predict's
// rows use them).
#include <fmt/format.h>

#include <array>
#include <cstddef>
#include <cstring>
#include <string_view>

#include "abbe/io/fixed6.hpp"

namespace abbe::io {

struct InPlaceRow {
  char* p;
  template <std::size_t N>
  void text(const char (&s)[N]) {  // a literal: fixed-size copy, no call
    std::memcpy(p, s, N - 1);
    p += N - 1;
  }
  void text(std::string_view s) {
    std::memcpy(p, s.data(), s.size());
    p += s.size();
  }
  // The first n characters of a fixed-size block, copied whole (no call).
  template <std::size_t M>
  void block(const std::array<char, M>& b, std::size_t n) {
    std::memcpy(p, b.data(), M);
    p += n;
  }
  void ch(char c) { *p++ = c; }
  void num(double v) { p = write_fixed6(p, v); }
  void uint(unsigned long long v) { p = write_decimal(p, v); }
};

struct AppendedRow {
  fmt::memory_buffer& b;
  template <std::size_t N>
  void text(const char (&s)[N]) {
    b.append(s, s + N - 1);
  }
  void text(std::string_view s) { b.append(s.data(), s.data() + s.size()); }
  template <std::size_t M>
  void block(const std::array<char, M>& s, std::size_t n) {
    b.append(s.data(), s.data() + n);
  }
  void ch(char c) { b.push_back(c); }
  void num(double v) { append_fixed6(b, v); }
  void uint(unsigned long long v) {
    char digits[24];
    b.append(digits, write_decimal(digits, v));
  }
};

}  // namespace abbe::io
