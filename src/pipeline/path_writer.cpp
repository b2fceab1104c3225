#include "abbe/pipeline/path_writer.hpp"

#include <array>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <iterator>
#include <string_view>

#include "abbe/io/input_error.hpp"
#include "abbe/io/row_text.hpp"

namespace abbe::pipeline {

using io::AppendedRow;
using io::fixed6_fits;
using io::InPlaceRow;
using io::kFixed6MaxChars;

namespace {
// Kind names padded to 8 bytes so that the fast path copies a fixed size.
struct KindName {
  std::array<char, 8> text;
  std::size_t size;
};
const KindName& kind_name(gcode::MotionKind kind) {
  static const KindName kRapid{{"rapid"}, 5}, kLinear{{"linear"}, 6}, kArc{{"arc"}, 3},
      kDwell{{"dwell"}, 5};
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

template <class Out>
void sign(Out& out, std::int8_t s) {
  if (s < 0)
    out.text("-1");
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
      out.text("{\"x\":");
    else
      out.text(",\n{\"x\":");
    out.num(pt.p.x());
    out.text(",\"y\":");
    out.num(pt.p.y());
    out.text(",\"z\":");
    out.num(pt.p.z());
  }
}

// The text around the middle fields, per format.
struct MiddleSyntax {
  const char* tool_length;
  const char* unknown_length;  // G43 with a tool of unknown length
  const char* line;
  const char* kind;
  const char* feed;
  const char* time;  // what comes before the tail's time
};
constexpr MiddleSyntax kCsvMiddle{",", "unknown", ",", ",", ",", ","};
constexpr MiddleSyntax kJsonMiddle{
    ",\"tool_length\":", "null", ",\"line\":", ",\"kind\":\"", "\",\"feed\":", ",\"time\":"};

template <class Out>
void format_middle(Out& out, PathFormat format, const path::PathPoint& pt) {
  const MiddleSyntax& syntax = format == PathFormat::csv ? kCsvMiddle : kJsonMiddle;
  out.text(syntax.tool_length);
  if (std::isnan(pt.tool_length))
    out.text(syntax.unknown_length);
  else
    out.num(pt.tool_length);
  out.text(syntax.line);
  out.uint(pt.line);
  out.text(syntax.kind);
  const KindName& kind = kind_name(pt.kind);
  out.block(kind.text, kind.size);
  out.text(syntax.feed);
  out.num(pt.feed);
  out.text(syntax.time);
}

// The JSON keys of the direction signs.
constexpr std::array<std::string_view, 3> kJsonDirKeys{",\"vx\":", ",\"vy\":", ",\"vz\":"};

template <class Out>
void format_tail(Out& out, PathFormat format, const path::PathPoint& pt) {
  const bool csv = format == PathFormat::csv;
  out.num(pt.time);
  for (std::size_t i = 0; i < 3; ++i) {
    if (csv)
      out.ch(',');
    else
      out.text(kJsonDirKeys[i]);
    sign(out, pt.dir[i]);
  }
  out.ch(csv ? '\n' : '}');
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
      InPlaceRow m{middle_.data()};
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
    InPlaceRow out{buffer_.data() + old_size};
    format_head(out, format_, pt, points_ == 0);
    std::memcpy(out.p, middle_.data(), middle_size_);
    out.p += middle_size_;
    format_tail(out, format_, pt);
    buffer_.resize(static_cast<std::size_t>(out.p - buffer_.data()));
  } else {
    AppendedRow out{buffer_};
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

}  // namespace abbe::pipeline
