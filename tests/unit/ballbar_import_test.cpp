// abbe import ballbar (io/ballbar.hpp): ISO 230-4 circular-test readings
// in a CSV of any column order and header case become measured data with
// the point on the circle, the radial normal, dn = the radial deviation,
// the signs of the last motion and one set per placement; bad input names
// the file, line, column and field.
#include <gtest/gtest.h>

#include <cmath>
#include <sstream>

#include "abbe/io/ballbar.hpp"
#include "abbe/io/input_error.hpp"

namespace abbe::io {
namespace {

MeasuredData read(const std::string& text) {
  std::istringstream in(text);
  return read_ballbar(in, "bb.csv");
}

std::string error_of(const std::string& text) {
  try {
    read(text);
  } catch (const InputError& e) {
    return format_input_error(e.where(), e.message());
  }
  return "accepted";
}

TEST(BallbarImport, ReadsAnyColumnOrderAndCase) {
  const MeasuredData d = read(
      "Angle;DR;Plane;Radius;CX;CY;CZ;Feed;Direction\n"
      "0;1,5;XY;150;-450;-200;-150;1000;CCW\n"
      "90;-2;XY;150;-450;-200;-150;1000;ccw\n"
      "# a comment\n"
      "180;0.25;XY;150;-450;-200;-150;1000;ccw\n"
      "90;3;ZX;100;0;0;-200;500;cw\n");
  ASSERT_EQ(d.rows.size(), 4u);
  EXPECT_TRUE(d.has_dn);
  const MeasuredRow& r0 = d.rows[0];
  EXPECT_NEAR((r0.p - Eigen::Vector3d(-300, -200, -150)).norm(), 0.0, 1e-9);
  EXPECT_NEAR((r0.n - Eigen::Vector3d(1, 0, 0)).norm(), 0.0, 1e-12);
  EXPECT_EQ(r0.dn, 1.5);  // decimal comma in a ;-separated file
  EXPECT_EQ(r0.line, 2u);
  // CCW at 0°: moving +Y; X was still moving +X (it reverses here).
  EXPECT_EQ(r0.v[1], 1);
  EXPECT_EQ(r0.v[0], 1);
  EXPECT_EQ(r0.set, "XY r150");
  const MeasuredRow& r1 = d.rows[1];
  EXPECT_NEAR((r1.p - Eigen::Vector3d(-450, -50, -150)).norm(), 0.0, 1e-9);
  EXPECT_NEAR((r1.n - Eigen::Vector3d(0, 1, 0)).norm(), 0.0, 1e-12);
  EXPECT_EQ(r1.v[0], -1);  // CCW at 90°: moving -X
  // Time from the feed: a quarter of a 150 mm circle at 1000 mm/min.
  EXPECT_NEAR(r1.t, 0.5 * 3.14159265358979323846 * 150.0 / 1000.0 * 60.0, 1e-9);
  EXPECT_NEAR(d.rows[2].t, 2.0 * r1.t, 1e-9);
  EXPECT_EQ(d.rows[2].line, 5u);
  // ZX: the angle turns from +Z towards +X; CW at 90° (on +X): moving +Z.
  const MeasuredRow& r3 = d.rows[3];
  EXPECT_NEAR((r3.p - Eigen::Vector3d(100, 0, -200)).norm(), 0.0, 1e-9);
  EXPECT_NEAR((r3.n - Eigen::Vector3d(1, 0, 0)).norm(), 0.0, 1e-12);
  EXPECT_EQ(r3.v[2], 1);
  EXPECT_EQ(r3.set, "ZX r100");
  EXPECT_EQ(r3.t, d.rows[2].t);  // a new circle: no time added between circles
  // The measured-data CSV it writes reads back the same.
  std::istringstream back(measured_data_to_csv(d));
  const MeasuredData again = read_measured_data(back, "again.csv");
  ASSERT_EQ(again.rows.size(), 4u);
  EXPECT_NEAR(again.rows[3].dn, 3.0, 1e-6);
  EXPECT_EQ(again.rows[3].set, "ZX r100");
}

TEST(BallbarImport, TimeAndSetColumnsAreKept) {
  const MeasuredData d = read(
      "plane,radius,cx,cy,cz,feed,direction,angle,dr,t,set\n"
      "YZ,50,0,0,0,800,-1,45,0.5,12.5,first\n");
  EXPECT_EQ(d.rows[0].t, 12.5);
  EXPECT_EQ(d.rows[0].set, "first");
  EXPECT_NEAR((d.rows[0].n - Eigen::Vector3d(0, std::sqrt(0.5), std::sqrt(0.5))).norm(), 0.0,
              1e-12);
}

TEST(BallbarImport, ErrorsNameFileLineColumnAndField) {
  const std::string head = "plane,radius,cx,cy,cz,feed,direction,angle,dr\n";
  EXPECT_NE(error_of("plane,radius,cx,cy,cz,feed,direction,angle\nXY,1,0,0,0,1,ccw,0\n")
                .find("bb.csv:1:1 [header]"),
            std::string::npos);
  EXPECT_NE(error_of(head + "XY,150,0,0,0,1000,ccw,0,1\nXX,150,0,0,0,1000,ccw,0,1\n")
                .find("bb.csv:3:1 [plane]"),
            std::string::npos);
  EXPECT_NE(error_of(head + "XY,-5,0,0,0,1000,ccw,0,1\n").find("bb.csv:2:4 [radius]"),
            std::string::npos);
  EXPECT_NE(error_of(head + "XY,5,0,0,0,0,ccw,0,1\n").find("bb.csv:2:12 [feed]"),
            std::string::npos);
  EXPECT_NE(error_of(head + "XY,5,0,0,0,10,up,0,1\n").find("bb.csv:2:15 [direction]"),
            std::string::npos);
  EXPECT_NE(error_of(head + "XY,5,0,0,0,10,cw,0,abc\n").find("bb.csv:2:20 [dr]"),
            std::string::npos);
  EXPECT_NE(error_of(head + "XY,5,0,0,0,10,cw,,1\n").find("[angle]"), std::string::npos);
  EXPECT_NE(error_of(head).find("no readings"), std::string::npos);
  EXPECT_THROW(load_ballbar("/nonexistent/bb.csv"), InputError);
}

}  // namespace
}  // namespace abbe::io
