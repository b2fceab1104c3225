#include "abbe/io/path_writer.hpp"

#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <iterator>

#include "abbe/io/input_error.hpp"

namespace abbe::io {

namespace {
constexpr double kScale = 1e6;       // 6 decimals
constexpr double kFastLimit = 9e12;  // |value| · 1e6 fits an int64 well below this

const char* kind_name(gcode::MotionKind kind) {
  switch (kind) {
    case gcode::MotionKind::rapid:
      return "rapid";
    case gcode::MotionKind::linear:
      return "linear";
    case gcode::MotionKind::arc:
      return "arc";
    case gcode::MotionKind::dwell:
      return "dwell";
  }
  return "unknown";
}

void append_str(fmt::memory_buffer& out, std::string_view s) {
  out.append(s.data(), s.data() + s.size());
}

void append_uint(fmt::memory_buffer& out, std::size_t value) {
  const fmt::format_int f(static_cast<unsigned long long>(value));
  out.append(f.data(), f.data() + f.size());
}

void append_sign(fmt::memory_buffer& out, std::int8_t s) {
  if (s < 0)
    append_str(out, "-1");
  else
    out.push_back(s > 0 ? '1' : '0');
}
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
  if (std::abs(value) >= kFastLimit) {
    fmt::format_to(std::back_inserter(out), "{:.6f}", value);
    return;
  }
  const long long scaled = std::llround(value * kScale);
  if (scaled < 0) out.push_back('-');
  const unsigned long long u = scaled < 0 ? 0ULL - static_cast<unsigned long long>(scaled)
                                          : static_cast<unsigned long long>(scaled);
  const fmt::format_int integer(u / 1000000ULL);
  out.append(integer.data(), integer.data() + integer.size());
  unsigned long long frac = u % 1000000ULL;
  if (frac == 0) return;
  char digits[7];
  int n = 6;
  while (frac % 10 == 0) {  // drop trailing zeros
    frac /= 10;
    --n;
  }
  digits[0] = '.';
  for (int i = n; i >= 1; --i) {
    digits[i] = static_cast<char>('0' + frac % 10);
    frac /= 10;
  }
  out.append(digits, digits + n + 1);
}

PathWriter::PathWriter(PathFormat format, ByteSink sink, std::size_t chunk_bytes)
    : format_(format), sink_(std::move(sink)), chunk_bytes_(chunk_bytes) {
  buffer_.reserve(chunk_bytes_ + 1024);
  if (format_ == PathFormat::csv)
    append_str(buffer_, "x,y,z,tool_length,line,kind,feed,time,vx,vy,vz\n");
  else
    append_str(buffer_, "[\n");
}

void PathWriter::write(const path::PathPoint& pt) {
  auto& b = buffer_;
  if (format_ == PathFormat::csv) {
    append_fixed6(b, pt.p.x());
    b.push_back(',');
    append_fixed6(b, pt.p.y());
    b.push_back(',');
    append_fixed6(b, pt.p.z());
    b.push_back(',');
    append_fixed6(b, pt.tool_length);
    b.push_back(',');
    append_uint(b, pt.line);
    b.push_back(',');
    append_str(b, kind_name(pt.kind));
    b.push_back(',');
    append_fixed6(b, pt.feed);
    b.push_back(',');
    append_fixed6(b, pt.time);
    b.push_back(',');
    append_sign(b, pt.dir[0]);
    b.push_back(',');
    append_sign(b, pt.dir[1]);
    b.push_back(',');
    append_sign(b, pt.dir[2]);
    b.push_back('\n');
  } else {
    append_str(b, points_ == 0 ? "{\"x\":" : ",\n{\"x\":");
    append_fixed6(b, pt.p.x());
    append_str(b, ",\"y\":");
    append_fixed6(b, pt.p.y());
    append_str(b, ",\"z\":");
    append_fixed6(b, pt.p.z());
    append_str(b, ",\"tool_length\":");
    append_fixed6(b, pt.tool_length);
    append_str(b, ",\"line\":");
    append_uint(b, pt.line);
    append_str(b, ",\"kind\":\"");
    append_str(b, kind_name(pt.kind));
    append_str(b, "\",\"feed\":");
    append_fixed6(b, pt.feed);
    append_str(b, ",\"time\":");
    append_fixed6(b, pt.time);
    append_str(b, ",\"vx\":");
    append_sign(b, pt.dir[0]);
    append_str(b, ",\"vy\":");
    append_sign(b, pt.dir[1]);
    append_str(b, ",\"vz\":");
    append_sign(b, pt.dir[2]);
    b.push_back('}');
  }
  ++points_;
  if (b.size() >= chunk_bytes_) flush();
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
