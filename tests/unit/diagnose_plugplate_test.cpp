// Real data: CMM measurements of two SDSS plug plates drilled on a
// Fanuc-controlled machine, against the owners' published fits
// (tests/data/plugplate, docs/diagnosis.md).
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <fstream>
#include <iostream>
#include <map>
#include <sstream>

#include "abbe/diagnose/diagnosis.hpp"
#include "abbe/diagnose/selection.hpp"
#include "abbe/io/plugplate.hpp"
#include "abbe/machine/machine.hpp"
#include "diagnose_test_problem.hpp"

namespace abbe::diagnose {
namespace {

const std::string kDir = std::string(ABBE_TEST_DATA_DIR) + "/plugplate/";
constexpr double kDegPerUrad = 180.0 / 3.14159265358979323846 * 1e-6;

struct PublishedFit {
  double offset_x = 0, offset_y = 0;  // mm
  double scale = 1, rot_deg = 0, qp = 0, qp_angle = 0;
};

PublishedFit read_fit(const std::string& file) {
  std::ifstream in(kDir + file);
  PublishedFit f;
  std::string key;
  std::string line;
  while (std::getline(in, line)) {
    std::istringstream s(line);
    s >> key;
    if (key == "FitOffset") s >> f.offset_x >> f.offset_y;
    if (key == "FitScale") s >> f.scale;
    if (key == "FitRotAngle") s >> f.rot_deg;
    if (key == "QPMagnitude") s >> f.qp;
    if (key == "QPAngle") s >> f.qp_angle;
    if (key == "DataTable") break;
  }
  return f;
}

struct PlateSetup {
  double ox = 0, oy = 0, rot_urad = 0;  // offset at the machine origin (µm), rotation (µrad)
  bool found = false;
};

// The setup of a plate from its diagnosis (the datum: a plate's offsets and
// rotation are always fitted): offsets at the set centroid moved to the
// origin with the rotation (Δ = θ·e_z × (0 − c)).
PlateSetup setup_of(const Diagnosis& d) {
  PlateSetup s;
  Eigen::Vector3d c = Eigen::Vector3d::Zero();
  for (const auto& st : d.datum) {
    const Term& t = st.term;
    if (t.kind == TermKind::setup_rotation && t.axis == 2) {
      s.rot_urad = t.coef[0];
      c = t.centre;
      s.found = true;
    }
  }
  for (const auto& st : d.datum) {
    const Term& t = st.term;
    if (t.kind == TermKind::setup_offset && t.direction == 0) s.ox = t.coef[0];
    if (t.kind == TermKind::setup_offset && t.direction == 1) s.oy = t.coef[0];
  }
  s.ox += 1e-3 * s.rot_urad * c.y();
  s.oy -= 1e-3 * s.rot_urad * c.x();
  return s;
}

const machine::Machine& plate_machine() {
  static const machine::Machine m = machine::Machine::load(kDir + "machine.yaml");
  return m;
}

TEST(DiagnosePlugPlate, SetupEqualsThePublishedFitWithinRounding) {
  for (const auto& [plate, fit_file] : std::map<std::string, std::string>{
           {"D8131_1", "fit_8131_1_2014-10-14.txt"}, {"D8132_1", "fit_8132_1_2014-10-14.txt"}}) {
    const PublishedFit pub = read_fit(fit_file);
    const io::MeasuredData data = io::load_plugplate(kDir + plate);
    const Diagnosis d = diagnose(plate_machine(), data, DiagnoseOptions{});
    std::cout << report_text(d);
    const PlateSetup s = setup_of(d);
    ASSERT_TRUE(s.found) << plate;
    // Published to 0.001 mm and 0.001°: within one unit of the last digit.
    EXPECT_NEAR(s.ox / 1000.0, pub.offset_x, 0.001) << plate;
    EXPECT_NEAR(s.oy / 1000.0, pub.offset_y, 0.001) << plate;
    EXPECT_NEAR(s.rot_urad * kDegPerUrad, pub.rot_deg, 0.001) << plate;
    std::cout << plate << ": offset " << s.ox / 1000 << ", " << s.oy / 1000 << " mm (published "
              << pub.offset_x << ", " << pub.offset_y << "), rotation " << s.rot_urad * kDegPerUrad
              << "° (published " << pub.rot_deg << "°)\n";
  }
}

// The linear map beyond the rigid setup: scale X, scale Y and the two
// squareness terms of the XY plane, fitted on top of the setup. Its
// symmetric traceless part is the owners' quadrupole.
struct LinearMap {
  double sx = 0, sy = 0, kxy = 0;  // ppm, ppm, µrad
  double quadrupole_ppm = 0;
  double delta_rss = 0, sigma2 = 0;  // what it removes, and the noise variance
};

LinearMap fit_linear_map(const Problem& pb, const std::string& set) {
  auto mk = [&](TermKind k, int a, int d) {
    Term t = test::make_term(k, a, d);
    t.set = set;
    return t;
  };
  const std::vector<Term> rigid = {mk(TermKind::setup_offset, 0, 0),
                                   mk(TermKind::setup_offset, 1, 1),
                                   mk(TermKind::setup_rotation, 2, -1)};
  const std::vector<Term> lin = {mk(TermKind::scale, 0, 0), mk(TermKind::scale, 1, 1),
                                 mk(TermKind::squareness, 1, 0)};  // with the rotation: both
                                                                   // off-diagonal terms
  auto fit = [&](const std::vector<Term>& ts, Eigen::VectorXd& beta) {
    Eigen::MatrixXd X(static_cast<Eigen::Index>(pb.obs.size()),
                      static_cast<Eigen::Index>(ts.size()));
    for (std::size_t i = 0; i < ts.size(); ++i)
      X.col(static_cast<Eigen::Index>(i)) = term_columns(pb, ts[i]);
    beta = (X.transpose() * X).ldlt().solve(X.transpose() * pb.y);
    return (pb.y - X * beta).squaredNorm();
  };
  std::vector<Term> all = rigid;
  all.insert(all.end(), lin.begin(), lin.end());
  Eigen::VectorXd b0, b1;
  const double rss0 = fit(rigid, b0), rss1 = fit(all, b1);
  LinearMap m;
  m.sx = b1[3];
  m.sy = b1[4];
  m.kxy = b1[5];
  // Linear map [[sx, kxy − θ], [θ, sy]]: its symmetric off-diagonal part is kxy/2.
  m.quadrupole_ppm = std::hypot(0.5 * (m.sx - m.sy), 0.5 * m.kxy);
  m.delta_rss = rss0 - rss1;
  m.sigma2 = rss1 / static_cast<double>(pb.obs.size() - all.size());
  return m;
}

TEST(DiagnosePlugPlate, ScaleAndSquarenessBeyondTheSetup) {
  for (const auto& [plate, fit_file] : std::map<std::string, std::string>{
           {"D8131_1", "fit_8131_1_2014-10-14.txt"}, {"D8132_1", "fit_8132_1_2014-10-14.txt"}}) {
    const PublishedFit pub = read_fit(fit_file);
    const io::MeasuredData data = io::load_plugplate(kDir + plate);
    const Problem pb = build_problem(plate_machine(), data, model::ModelKind::ae_arm, nullptr);
    const LinearMap m = fit_linear_map(pb, data.rows[0].set);
    std::cout << plate << ": scale X " << m.sx << " ppm, scale Y " << m.sy << " ppm, squareness "
              << m.kxy << " µrad, quadrupole " << m.quadrupole_ppm << " ppm (published "
              << pub.qp * 1e6 << "), ΔRSS/σ² " << m.delta_rss / m.sigma2 << " for 3 columns\n";
    // Scale mismatch and squareness together (3 columns beyond the rigid
    // setup) are significant on both plates at the 1 % level of χ²_3…
    EXPECT_GT(m.delta_rss / m.sigma2, 11.3) << plate;
    // …and of the order of the owners' quadrupole (their QP is fitted after
    // fixing scale and rotation; docs/diagnosis.md compares the numbers).
    EXPECT_GT(m.quadrupole_ppm, 0.5 * pub.qp * 1e6) << plate;
    EXPECT_LT(m.quadrupole_ppm, 50.0) << plate;
  }
}

// Transfer over every ordered pair of the plates in tests/data (two plates:
// two pairs): the non-datum part of the extended model fitted on plate A
// applied to plate B, whose own datum (offset X, Y and rotation, a new
// fixture placement) is always refitted. Printed as the table of
// docs/diagnosis.md ("Gain on the plate not used for the fit").
TEST(DiagnosePlugPlate, TransferOverAllOrderedPairsOfThePlates) {
  const std::vector<std::pair<std::string, std::string>> plates{{"D8131_1", "8131"},
                                                                {"D8132_1", "8132"}};
  int pairs = 0, better = 0, worse = 0;
  for (const auto& [file_a, id_a] : plates)
    for (const auto& [file_b, id_b] : plates) {
      if (file_a == file_b) continue;
      const io::MeasuredData a = io::load_plugplate(kDir + file_a);
      const io::MeasuredData b = io::load_plugplate(kDir + file_b);
      const Diagnosis da = diagnose(plate_machine(), a, DiagnoseOptions{});
      Overlay transfer;
      for (const auto& st : da.effects)
        if (st.term.kind != TermKind::setup_offset && st.term.kind != TermKind::setup_rotation)
          transfer.terms.push_back(st.term);
      auto rigid_rms = [&, id = id_b](const Overlay* extend) {
        const Problem pb = build_problem(plate_machine(), b, model::ModelKind::ae_arm, extend);
        std::vector<Term> ts(3);
        for (int i = 0; i < 3; ++i) {
          ts[static_cast<std::size_t>(i)].kind =
              i < 2 ? TermKind::setup_offset : TermKind::setup_rotation;
          ts[static_cast<std::size_t>(i)].axis = i < 2 ? i : 2;
          ts[static_cast<std::size_t>(i)].direction = i < 2 ? i : -1;
          ts[static_cast<std::size_t>(i)].set = id;
        }
        Eigen::MatrixXd X(static_cast<Eigen::Index>(pb.obs.size()), 3);
        for (int i = 0; i < 3; ++i) X.col(i) = term_columns(pb, ts[static_cast<std::size_t>(i)]);
        const Eigen::VectorXd beta = (X.transpose() * X).ldlt().solve(X.transpose() * pb.y);
        return residual_stats(pb, pb.y - X * beta).rms_um;
      };
      const double base = rigid_rms(nullptr), ext = rigid_rms(&transfer);
      std::cout << id_a << " → " << id_b << ": " << transfer.terms.size()
                << " transferred terms, RMS after the datum fit " << base << " µm → " << ext
                << " µm (" << 100.0 * (1.0 - ext / base) << " %)\n";
      ++pairs;
      better += ext < base * (1.0 - 1e-9) ? 1 : 0;
      worse += ext > base * (1.0 + 1e-9) ? 1 : 0;
      if (id_b == "8132") {
        EXPECT_NEAR(base, 7.93, 0.01);  // published 8132 RMS: 8.1 µm (radial)
      }
      // What one plate teaches beyond its datum need not carry over: the
      // extension must not make the other plate worse by more than noise.
      EXPECT_LT(ext, base * 1.15) << id_a << " → " << id_b;
    }
  std::cout << "all ordered pairs: " << pairs << ", better " << better << ", worse " << worse
            << ", unchanged " << pairs - better - worse << "\n";
  EXPECT_EQ(pairs, 2);
}

}  // namespace
}  // namespace abbe::diagnose
