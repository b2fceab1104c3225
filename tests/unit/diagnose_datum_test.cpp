// The datum on circular tests and the travel check of the measured points
// (diagnosis.hpp). A ballbar reads the deviation along the radius, so a
// rotation of its circle about the circle's own axis is invisible. On a
// closed circle its column vanishes. On a partial arc (ISO 230-4 allows
// them where the table is in the way, e.g. 220° in ZX), or a closed circle
// that repeats its first reading, the centroid lies off the centre. The
// rotation about the centroid is then a tangential part, zero up to the
// file's rounding, plus a constant shift that the offsets already take. The
// datum must keep the offsets alone, with their true values and
// uncertainties, and no rotation.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <sstream>
#include <string>

#include "abbe/diagnose/diagnosis.hpp"
#include "abbe/io/ballbar.hpp"
#include "abbe/io/measured_data.hpp"
#include "abbe/machine/machine.hpp"

namespace abbe::diagnose {
namespace {

constexpr double kPi = 3.14159265358979323846;

// The plug-plate machine: every table zero, travel ±400 mm in X and Y.
const machine::Machine& zero_machine() {
  static const machine::Machine m =
      machine::Machine::load(std::string(ABBE_TEST_DATA_DIR) + "/plugplate/machine.yaml");
  return m;
}

// Ballbar readings in XY, r = 100 mm about (cx, cy, 0): an arc from
// `start` over `arc` degrees, a reading every degree, CCW then CW; the
// circle's centre is off by (ox, oy) µm (a datum the fit must find) and the
// readings carry 0.3 µm of noise. `closed`: the last reading repeats the
// first (360° and 0°), as software that writes both ends does.
io::MeasuredData arc(double cx, double cy, double start, double arc_deg, bool closed, double ox,
                     double oy, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> noise(0.0, 0.3);
  std::string csv = "plane,radius,cx,cy,cz,feed,direction,angle,dr\n";
  const int n = static_cast<int>(std::lround(arc_deg)) + (closed ? 1 : 0);
  for (int way : {1, -1})
    for (int k = 0; k < n; ++k) {
      const double a = way > 0 ? start + k : start + arc_deg - k;
      const double th = a * kPi / 180.0;
      // A centre off by (ox, oy) moves every point by it: dr = o·n.
      const double dr = ox * std::cos(th) + oy * std::sin(th) + noise(rng);
      csv +=
          fmt::format("XY,100,{},{},0,1000,{},{},{:.6f}\n", cx, cy, way > 0 ? "ccw" : "cw", a, dr);
    }
  std::istringstream in(csv);
  // Through the measured-data file `abbe import ballbar` writes, whose
  // positions and normals carry 6 decimals: what the diagnosis reads.
  std::istringstream measured(io::measured_data_to_csv(io::read_ballbar(in, "<arc>")));
  return io::read_measured_data(measured, "<arc measured>");
}

void expect_offsets_only(const Diagnosis& d, double ox, double oy) {
  ASSERT_EQ(d.datum.size(), 2u) << report_text(d);
  for (const SelectedTerm& st : d.datum) {
    ASSERT_EQ(st.term.kind, TermKind::setup_offset) << st.term.label();
    const double want = st.term.axis == 0 ? ox : oy;
    ASSERT_EQ(st.term.stderr_.size(), 1u);
    // 0.3 µm noise over 440–720 readings: u ≈ 0.02 µm.
    EXPECT_LT(st.term.stderr_[0], 0.05) << st.term.label();
    EXPECT_NEAR(st.term.coef[0], want, 4.0 * st.term.stderr_[0] + 1e-3) << st.term.label();
  }
  EXPECT_TRUE(d.effects.empty()) << report_text(d);
}

TEST(DiagnoseDatum, APartialArcKeepsItsOffsetsAndNoRotation) {
  for (std::uint64_t seed : {1u, 2u, 3u}) {
    const io::MeasuredData data = arc(-150.0, 100.0, -20.0, 220.0, false, 1.5, -0.8, seed);
    expect_offsets_only(diagnose(zero_machine(), data, DiagnoseOptions{}), 1.5, -0.8);
  }
}

TEST(DiagnoseDatum, AClosedCircleThatRepeatsItsFirstReadingKeepsItsOffsets) {
  const io::MeasuredData data = arc(120.0, -60.0, 0.0, 360.0, true, -0.6, 2.2, 4);
  expect_offsets_only(diagnose(zero_machine(), data, DiagnoseOptions{}), -0.6, 2.2);
}

TEST(DiagnoseDatum, AClosedCircleKeepsItsOffsets) {
  const io::MeasuredData data = arc(0.0, 0.0, 0.0, 360.0, false, 0.9, 0.4, 5);
  expect_offsets_only(diagnose(zero_machine(), data, DiagnoseOptions{}), 0.9, 0.4);
}

TEST(DiagnoseTravel, PointsOutsideTheTravelAreCountedAndNamedInTheReport) {
  // A circle whose right part lies beyond X's travel end (+400 mm).
  const io::MeasuredData data = arc(350.0, 0.0, 0.0, 360.0, false, 0.0, 0.0, 6);
  const Diagnosis d = diagnose(zero_machine(), data, DiagnoseOptions{});
  std::size_t beyond = 0;
  for (const io::MeasuredRow& r : data.rows) beyond += r.p.x() > 400.0 ? 1 : 0;
  ASSERT_GT(beyond, 0u);
  EXPECT_EQ(d.outside_travel_points, beyond);
  const std::string w = travel_warning(d);
  EXPECT_NE(w.find(fmt::format("{} of {} points outside the travel", beyond, data.rows.size())),
            std::string::npos)
      << w;
  EXPECT_NE(w.find("machine coordinates"), std::string::npos) << w;
  EXPECT_NE(report_text(d).find("warning: " + w), std::string::npos);
  EXPECT_NE(report_json(d).find("\"travel_warning\""), std::string::npos);
}

TEST(DiagnoseTravel, PointsInsideTheTravelGiveNoWarning) {
  const Diagnosis d =
      diagnose(zero_machine(), arc(0.0, 0.0, 0.0, 360.0, false, 0.0, 0.0, 7), DiagnoseOptions{});
  EXPECT_EQ(d.outside_travel_points, 0u);
  EXPECT_TRUE(travel_warning(d).empty());
  EXPECT_EQ(report_text(d).find("warning:"), std::string::npos);
  EXPECT_EQ(report_json(d).find("\"travel_warning\""), std::string::npos);
}

}  // namespace
}  // namespace abbe::diagnose
