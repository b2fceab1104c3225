#pragma once
// PathWriter: streams PathPoints as CSV or as a JSON array, formatting into a
// large buffer that is handed to a byte sink in big chunks (fast enough to
// keep up with the front end; memory does not grow with the path).
//
// CSV: header `x,y,z,tool_length,line,kind,feed,time,vx,vy,vz`, one row per
// point. JSON: an array of objects with the same keys. Lengths in mm, feed in
// mm/min, time in s, all written with 6 decimals (trailing zeros dropped);
// kind ∈ {rapid, linear, arc}; vx, vy, vz ∈ {-1, 0, 1}.
#include <fmt/format.h>

#include <array>
#include <cstddef>
#include <functional>
#include <string>
#include <string_view>

#include "abbe/io/fixed6.hpp"
#include "abbe/path/path_point.hpp"

namespace abbe::pipeline {

enum class PathFormat { csv, json };

// "csv" or "json"; throws abbe::InputError (field "--format") otherwise.
PathFormat parse_path_format(std::string_view name);

// Receives the formatted bytes, a chunk at a time.
using ByteSink = std::function<void(const char* data, std::size_t size)>;

class PathWriter {
 public:
  PathWriter(PathFormat format, ByteSink sink, std::size_t chunk_bytes = std::size_t{1} << 20);
  ~PathWriter() =
      default;  // does not flush: call finish() (an error path leaves the output incomplete)
  PathWriter(const PathWriter&) = delete;
  PathWriter& operator=(const PathWriter&) = delete;

  void write(const path::PathPoint& point);
  // Writes the trailer (JSON's closing bracket) and hands on what is buffered.
  void finish();
  std::size_t points() const { return points_; }

 private:
  void flush();

  PathFormat format_;
  ByteSink sink_;
  std::size_t chunk_bytes_;
  fmt::memory_buffer buffer_;
  std::size_t points_ = 0;
  bool finished_ = false;
  // The formatted columns that stay the same along a motion (see the .cpp).
  std::array<char, 256> middle_{};
  std::size_t middle_size_ = 0;
  bool middle_valid_ = false;
  std::size_t middle_line_ = 0;
  gcode::MotionKind middle_kind_ = gcode::MotionKind::rapid;
  double middle_tool_length_ = 0.0;
  double middle_feed_ = 0.0;
};

}  // namespace abbe::pipeline
