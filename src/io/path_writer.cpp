#include "abbe/io/path_writer.hpp"

#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <iterator>

#include "abbe/io/input_error.hpp"

namespace abbe::io {

namespace {
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
  void num(double v) { p = write_fixed6(p, v); }
  void uint(std::size_t v) { p = write_decimal(p, static_cast<unsigned long long>(v)); }
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
    b.append(digits, write_decimal(digits, static_cast<unsigned long long>(v)));
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

void append_fixed6(fmt::memory_buffer& out, double value) {
  if (!std::isfinite(value)) {
    append_str(out, std::isnan(value) ? "nan" : (value > 0 ? "inf" : "-inf"));
    return;
  }
  if (!fixed6_fits(value)) {
    fmt::format_to(std::back_inserter(out), "{:.6f}", value);
    return;
  }
  char digits[32];
  out.append(digits, write_fixed6(digits, value));
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
  const bool fast = fixed6_fits(pt.p.x()) && fixed6_fits(pt.p.y()) && fixed6_fits(pt.p.z()) &&
                    fixed6_fits(pt.tool_length) && fixed6_fits(pt.feed) && fixed6_fits(pt.time);
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
