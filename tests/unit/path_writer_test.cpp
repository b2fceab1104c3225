// PathWriter: number formatting, CSV and JSON streaming, chunking.
#include "abbe/pipeline/path_writer.hpp"

#include <gtest/gtest.h>

#include <cstdlib>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "abbe/io/input_error.hpp"

namespace abbe::pipeline {
namespace {

using io::append_fixed6;

std::string fixed(double v) {
  fmt::memory_buffer b;
  append_fixed6(b, v);
  return fmt::to_string(b);
}

TEST(PathWriter, FixedSixDecimalsDropsTrailingZeros) {
  EXPECT_EQ(fixed(0.0), "0");
  EXPECT_EQ(fixed(-350.0), "-350");
  EXPECT_EQ(fixed(1.5), "1.5");
  EXPECT_EQ(fixed(-0.25), "-0.25");
  EXPECT_EQ(fixed(0.1 + 0.2), "0.3");
  EXPECT_EQ(fixed(123.4567894), "123.456789");
  EXPECT_EQ(fixed(123.4567896), "123.45679");
  EXPECT_EQ(fixed(-0.000001), "-0.000001");
  EXPECT_EQ(fixed(1e-7), "0");
  EXPECT_EQ(fixed(-1e-7), "0");
  EXPECT_EQ(fixed(1e13), "10000000000000.000000");
  // Round trip to 6 decimals for a spread of values.
  for (double v = -987.654321; v < 987.0; v += 13.3333337) {
    const double back = std::strtod(fixed(v).c_str(), nullptr);
    EXPECT_NEAR(back, v, 5.000001e-7) << fixed(v);
  }
}

std::vector<path::PathPoint> sample_points() {
  std::vector<path::PathPoint> pts(3);
  pts[0].p = Eigen::Vector3d(-350.0, -150.0, -280.0);
  pts[0].tool_length = 200.0;
  pts[0].line = 3;
  pts[0].kind = gcode::MotionKind::rapid;
  pts[1].p = Eigen::Vector3d(-355.125, -150.0, -280.0);
  pts[1].tool_length = 200.0;
  pts[1].line = 4;
  pts[1].kind = gcode::MotionKind::linear;
  pts[1].feed = 500.0;
  pts[1].time = 0.615;
  pts[1].dir = {-1, 0, 0};
  pts[2].p = Eigen::Vector3d(-360.0, -149.5, -280.0);
  pts[2].line = 5;
  pts[2].kind = gcode::MotionKind::arc;
  pts[2].feed = 250.0;
  pts[2].time = 1.25;
  pts[2].dir = {-1, 1, -1};
  return pts;
}

std::string write_all(PathFormat format, const std::vector<path::PathPoint>& pts,
                      std::size_t chunk = 1 << 20, int* calls = nullptr) {
  std::string out;
  PathWriter writer(
      format,
      [&](const char* d, std::size_t n) {
        out.append(d, n);
        if (calls) ++*calls;
      },
      chunk);
  for (const auto& p : pts) writer.write(p);
  writer.finish();
  EXPECT_EQ(writer.points(), pts.size());
  return out;
}

TEST(PathWriter, CsvHasHeaderAndOneRowPerPoint) {
  const std::string csv = write_all(PathFormat::csv, sample_points());
  EXPECT_EQ(csv,
            "x,y,z,tool_length,line,kind,feed,time,vx,vy,vz\n"
            "-350,-150,-280,200,3,rapid,0,0,0,0,0\n"
            "-355.125,-150,-280,200,4,linear,500,0.615,-1,0,0\n"
            "-360,-149.5,-280,0,5,arc,250,1.25,-1,1,-1\n");
}

TEST(PathWriter, ColumnsThatChangeWithinALineAreRewritten) {
  // Points of one source line whose feed, kind or tool length change (the
  // writer reuses the formatted middle columns only while all are equal).
  std::vector<path::PathPoint> pts(4);
  for (auto& p : pts) {
    p.line = 7;
    p.kind = gcode::MotionKind::linear;
    p.feed = 500.0;
    p.tool_length = 100.0;
  }
  pts[1].p.x() = 1.0;
  pts[2].feed = 600.0;
  pts[3].feed = 600.0;
  pts[3].kind = gcode::MotionKind::arc;
  pts[3].tool_length = 100.5;
  EXPECT_EQ(write_all(PathFormat::csv, pts),
            "x,y,z,tool_length,line,kind,feed,time,vx,vy,vz\n"
            "0,0,0,100,7,linear,500,0,0,0,0\n"
            "1,0,0,100,7,linear,500,0,0,0,0\n"
            "0,0,0,100,7,linear,600,0,0,0,0\n"
            "0,0,0,100.5,7,arc,600,0,0,0,0\n");
  const auto doc = nlohmann::json::parse(write_all(PathFormat::json, pts));
  EXPECT_EQ(doc[1]["feed"], 500);
  EXPECT_EQ(doc[2]["feed"], 600);
  EXPECT_EQ(doc[3]["kind"], "arc");
  EXPECT_EQ(doc[3]["tool_length"], 100.5);
}

TEST(PathWriter, HugeValuesTakeTheSlowPathInTheSameFormat) {
  std::vector<path::PathPoint> pts(2);
  pts[0].line = 1;
  pts[1].line = 1;
  pts[1].time = 2e13;  // beyond the fast integer path
  EXPECT_EQ(write_all(PathFormat::csv, pts),
            "x,y,z,tool_length,line,kind,feed,time,vx,vy,vz\n"
            "0,0,0,0,1,rapid,0,0,0,0,0\n"
            "0,0,0,0,1,rapid,0,20000000000000.000000,0,0,0\n");
}

TEST(PathWriter, JsonIsAnArrayOfObjectsWithTheCsvKeys) {
  const auto pts = sample_points();
  const auto doc = nlohmann::json::parse(write_all(PathFormat::json, pts));
  ASSERT_TRUE(doc.is_array());
  ASSERT_EQ(doc.size(), pts.size());
  EXPECT_EQ(doc[1]["x"].get<double>(), -355.125);
  EXPECT_EQ(doc[1]["kind"], "linear");
  EXPECT_EQ(doc[1]["line"], 4);
  EXPECT_EQ(doc[2]["vz"], -1);
  EXPECT_EQ(doc[2]["time"].get<double>(), 1.25);
  for (const char* key :
       {"x", "y", "z", "tool_length", "line", "kind", "feed", "time", "vx", "vy", "vz"})
    EXPECT_TRUE(doc[0].contains(key)) << key;
  EXPECT_EQ(doc[0].size(), 11u);

  const auto empty = nlohmann::json::parse(write_all(PathFormat::json, {}));
  EXPECT_TRUE(empty.is_array());
  EXPECT_TRUE(empty.empty());
}

TEST(PathWriter, SmallChunksGiveTheSameBytes) {
  std::vector<path::PathPoint> many;
  for (int i = 0; i < 200; ++i)
    for (const auto& p : sample_points()) many.push_back(p);
  int calls = 0;
  const std::string big = write_all(PathFormat::csv, many);
  const std::string small = write_all(PathFormat::csv, many, 256, &calls);
  EXPECT_EQ(big, small);
  EXPECT_GT(calls, 10);
}

TEST(PathWriter, ParsesFormatNames) {
  EXPECT_EQ(parse_path_format("csv"), PathFormat::csv);
  EXPECT_EQ(parse_path_format("json"), PathFormat::json);
  EXPECT_THROW(parse_path_format("xml"), InputError);
}

}  // namespace
}  // namespace abbe::pipeline
