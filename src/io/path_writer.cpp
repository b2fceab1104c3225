#include "abbe/io/path_writer.hpp"

#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <iterator>

#include "abbe/io/input_error.hpp"

namespace abbe::io {

namespace {
constexpr double kScale = 1e6;  // 6 decimals

// Kind names padded to 8 bytes so that the fast path copies a fixed size.
struct KindName {
  char text[8];
  std::size_t size;
};
const KindName& kind_name(gcode::MotionKind kind) {
  static const KindName kRapid{"rapid", 5}, kLinear{"linear", 6}, kArc{"arc", 3},
      kDwell{"dwell", 5};
  switch (kind) {
    case gcode::MotionKind::rapid:
      return kRapid;
    case gcode::MotionKind::linear:
      return kLinear;
    case gcode::MotionKind::arc:
      return kArc;
    case gcode::MotionKind::dwell:
      break;
  }
  return kDwell;
}

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

// Writes the n = count_digits(v) digits of v ending at p + n, backwards.
void write_digits_backwards(char* end, unsigned long long v) {
  while (v >= 100) {
    const auto pair = static_cast<std::size_t>(v % 100) * 2;
    v /= 100;
    end -= 2;
    std::memcpy(end, kDigitPairs + pair, 2);
  }
  if (v >= 10) {
    end -= 2;
    std::memcpy(end, kDigitPairs + static_cast<std::size_t>(v) * 2, 2);
  } else {
    *--end = static_cast<char>('0' + v);
  }
}

char* write_uint(char* p, unsigned long long v) {
  const int n = count_digits(v);
  write_digits_backwards(p + n, v);
  return p + n;
}

#if defined(__BYTE_ORDER__) && __BYTE_ORDER__ == __ORDER_BIG_ENDIAN__
// Big-endian: digit by digit.
char* write_fixed6_fast(char* p, double value) {
  const double scaled = value * kScale;
  const long long r = static_cast<long long>(scaled < 0.0 ? scaled - 0.5 : scaled + 0.5);
  if (r < 0) *p++ = '-';
  const unsigned long long u =
      r < 0 ? 0ULL - static_cast<unsigned long long>(r) : static_cast<unsigned long long>(r);
  p = write_uint(p, u / 1000000ULL);
  const auto frac = static_cast<unsigned>(u % 1000000ULL);
  if (frac == 0) return p;
  p[0] = '.';
  std::memcpy(p + 1, kDigitPairs + (frac / 10000) * 2, 2);
  std::memcpy(p + 3, kDigitPairs + (frac / 100 % 100) * 2, 2);
  std::memcpy(p + 5, kDigitPairs + (frac % 100) * 2, 2);
  char* end = p + 7;
  while (end[-1] == '0') --end;
  return end;
}
#else
// Little-endian: the digits are assembled in a register (the first character
// in the lowest byte) and stored with one unaligned write, the lengths
// computed without branches (the digit counts of a column vary from row to
// row, which a branch predictor cannot follow).

// "000" … "999" as 32-bit words (the first character in the lowest byte, the
// fourth byte zero): three digits per table lookup.
struct DigitTriples {
  std::uint32_t word[1000];
  constexpr DigitTriples() : word() {
    for (std::uint32_t i = 0; i < 1000; ++i)
      word[i] = (48 + i / 100) | (48 + i / 10 % 10) << 8 | (48 + i % 10) << 16;
  }
};
constexpr DigitTriples kDigitTriples;

// The format of append_fixed6 for fixed6_fits(value) (|value| < 9e12, so that
// value · 1e6 fits an int64): at most 21 characters at p (up to 24 bytes
// stored); returns one past the last character.
char* write_fixed6_fast(char* p, double value) {
  // Round half away from zero (printf differs only at exact binary ties).
  const double scaled = value * kScale;
  const long long r = static_cast<long long>(scaled + std::copysign(0.5, scaled));
  *p = '-';
  p += r < 0;
  const unsigned long long u =
      r < 0 ? 0ULL - static_cast<unsigned long long>(r) : static_cast<unsigned long long>(r);
  const unsigned long long int_part = u / 1000000ULL;
  const auto frac = static_cast<std::uint32_t>(u - int_part * 1000000ULL);
  if (int_part < 1000) {
    // Up to three digits: one lookup, the leading zeros shifted out.
    const auto v = static_cast<std::uint32_t>(int_part);
    const std::uint32_t n = 1u + (v >= 10) + (v >= 100);
    const std::uint32_t w = kDigitTriples.word[v] >> (8 * (3 - n));
    std::memcpy(p, &w, 4);
    p += n;
  } else {
    p = write_uint(p, int_part);
  }
  if (frac == 0) return p;
  // ".dddddd" and a zero byte in one store; keep the digits up to the last
  // nonzero one (trailing zeros dropped).
  const std::uint64_t digits = std::uint64_t{kDigitTriples.word[frac / 1000]} |
                               std::uint64_t{kDigitTriples.word[frac % 1000]} << 24;
  const std::uint64_t w = '.' | digits << 8;
  std::memcpy(p, &w, 8);
  const std::uint64_t values = digits ^ 0x303030303030ULL;  // digit values, nonzero: frac > 0
  const int last = (63 - __builtin_clzll(values)) / 8;      // byte of the last nonzero digit
  return p + 2 + last;
}
#endif

bool fast_number(double value) { return fixed6_fits(value); }

void append_str(fmt::memory_buffer& out, std::string_view s) {
  out.append(s.data(), s.data() + s.size());
}

// Row output into memory with room for kMaxFastRow bytes (all numbers on the fast path).
struct CharOut {
  char* p;
  template <std::size_t N>
  void str(const char (&s)[N]) {  // a literal: fixed-size copy
    std::memcpy(p, s, N - 1);
    p += N - 1;
  }
  void kind(const KindName& k) {
    std::memcpy(p, k.text, sizeof(k.text));
    p += k.size;
  }
  void ch(char c) { *p++ = c; }
  void num(double v) { p = write_fixed6_fast(p, v); }
  void uint(std::size_t v) { p = write_uint(p, static_cast<unsigned long long>(v)); }
};

// Row output appended to the buffer (any number, including the slow ones).
struct BufferOut {
  fmt::memory_buffer& b;
  template <std::size_t N>
  void str(const char (&s)[N]) {
    b.append(s, s + N - 1);
  }
  void kind(const KindName& k) { b.append(k.text, k.text + k.size); }
  void ch(char c) { b.push_back(c); }
  void num(double v) { append_fixed6(b, v); }
  void uint(std::size_t v) {
    char digits[24];
    b.append(digits, write_uint(digits, static_cast<unsigned long long>(v)));
  }
};

template <class Out>
void sign(Out& out, std::int8_t s) {
  if (s < 0)
    out.str("-1");
  else
    out.ch(s > 0 ? '1' : '0');
}

// A row is head (x, y, z), middle (tool length, line, kind, feed: the same
// for all points of a motion, so the fast path formats it once per motion)
// and tail (time, direction signs).
template <class Out>
void format_head(Out& out, PathFormat format, const path::PathPoint& pt, bool first) {
  if (format == PathFormat::csv) {
    out.num(pt.p.x());
    out.ch(',');
    out.num(pt.p.y());
    out.ch(',');
    out.num(pt.p.z());
  } else {
    if (first)
      out.str("{\"x\":");
    else
      out.str(",\n{\"x\":");
    out.num(pt.p.x());
    out.str(",\"y\":");
    out.num(pt.p.y());
    out.str(",\"z\":");
    out.num(pt.p.z());
  }
}

template <class Out>
void format_middle(Out& out, PathFormat format, const path::PathPoint& pt) {
  if (format == PathFormat::csv) {
    out.ch(',');
    out.num(pt.tool_length);
    out.ch(',');
    out.uint(pt.line);
    out.ch(',');
    out.kind(kind_name(pt.kind));
    out.ch(',');
    out.num(pt.feed);
    out.ch(',');
  } else {
    out.str(",\"tool_length\":");
    out.num(pt.tool_length);
    out.str(",\"line\":");
    out.uint(pt.line);
    out.str(",\"kind\":\"");
    out.kind(kind_name(pt.kind));
    out.str("\",\"feed\":");
    out.num(pt.feed);
    out.str(",\"time\":");
  }
}

template <class Out>
void format_tail(Out& out, PathFormat format, const path::PathPoint& pt) {
  out.num(pt.time);
  if (format == PathFormat::csv) {
    out.ch(',');
    sign(out, pt.dir[0]);
    out.ch(',');
    sign(out, pt.dir[1]);
    out.ch(',');
    sign(out, pt.dir[2]);
    out.ch('\n');
  } else {
    out.str(",\"vx\":");
    sign(out, pt.dir[0]);
    out.str(",\"vy\":");
    sign(out, pt.dir[1]);
    out.str(",\"vz\":");
    sign(out, pt.dir[2]);
    out.ch('}');
  }
}

// Longest row of the fast path: 6 numbers of at most kFixed6MaxChars bytes
// stored, a line number of at most 20, the JSON keys and punctuation (< 120),
// the kind copied as 8 bytes.
constexpr std::size_t kMaxFastRow = 6 * kFixed6MaxChars + 20 + 160;
}  // namespace

PathFormat parse_path_format(std::string_view name) {
  if (name == "csv") return PathFormat::csv;
  if (name == "json") return PathFormat::json;
  SourceLocation where;
  where.file = "<command line>";
  where.field = "--format";
  throw InputError(where, "unknown path format '" + std::string(name) + "' (expected csv or json)");
}

char* write_fixed6(char* out, double value) { return write_fixed6_fast(out, value); }

char* write_decimal(char* out, unsigned long long v) { return write_uint(out, v); }

void append_fixed6(fmt::memory_buffer& out, double value) {
  if (!std::isfinite(value)) {
    append_str(out, std::isnan(value) ? "nan" : (value > 0 ? "inf" : "-inf"));
    return;
  }
  if (!fast_number(value)) {
    fmt::format_to(std::back_inserter(out), "{:.6f}", value);
    return;
  }
  char digits[32];
  out.append(digits, write_fixed6_fast(digits, value));
}

PathWriter::PathWriter(PathFormat format, ByteSink sink, std::size_t chunk_bytes)
    : format_(format), sink_(std::move(sink)), chunk_bytes_(chunk_bytes) {
  buffer_.reserve(chunk_bytes_ + 2 * kMaxFastRow);
  if (format_ == PathFormat::csv)
    append_str(buffer_, "x,y,z,tool_length,line,kind,feed,time,vx,vy,vz\n");
  else
    append_str(buffer_, "[\n");
}

void PathWriter::write(const path::PathPoint& pt) {
  const bool fast = fast_number(pt.p.x()) && fast_number(pt.p.y()) && fast_number(pt.p.z()) &&
                    fast_number(pt.tool_length) && fast_number(pt.feed) && fast_number(pt.time);
  if (fast) {
    if (!middle_valid_ || pt.line != middle_line_ || pt.kind != middle_kind_ ||
        pt.tool_length != middle_tool_length_ || pt.feed != middle_feed_) {
      CharOut m{middle_.data()};
      format_middle(m, format_, pt);
      middle_size_ = static_cast<std::size_t>(m.p - middle_.data());
      middle_line_ = pt.line;
      middle_kind_ = pt.kind;
      middle_tool_length_ = pt.tool_length;
      middle_feed_ = pt.feed;
      middle_valid_ = true;
    }
    // Format in place at the end of the buffer (no intermediate copy).
    const std::size_t old_size = buffer_.size();
    buffer_.resize(old_size + kMaxFastRow);
    CharOut out{buffer_.data() + old_size};
    format_head(out, format_, pt, points_ == 0);
    std::memcpy(out.p, middle_.data(), middle_size_);
    out.p += middle_size_;
    format_tail(out, format_, pt);
    buffer_.resize(static_cast<std::size_t>(out.p - buffer_.data()));
  } else {
    BufferOut out{buffer_};
    format_head(out, format_, pt, points_ == 0);
    format_middle(out, format_, pt);
    format_tail(out, format_, pt);
  }
  ++points_;
  if (buffer_.size() >= chunk_bytes_) flush();
}

void PathWriter::flush() {
  if (buffer_.size() == 0) return;
  sink_(buffer_.data(), buffer_.size());
  buffer_.clear();
}

void PathWriter::finish() {
  if (finished_) return;
  finished_ = true;
  if (format_ == PathFormat::json) append_str(buffer_, points_ == 0 ? "]\n" : "\n]\n");
  flush();
}

}  // namespace abbe::io
