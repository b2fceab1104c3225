// Controller tables (`abbe export`): LinuxCNC per-joint files and the
// volumetric grid. A zero-error machine gives all-zero tables; a machine
// with only EXX gives the hand-computed file and corrects the samples
// exactly; on the sample machine the tables, applied as a control applies
// them (linear along the joint, trilinear in the grid), leave the predicted
// deviation of the nc-samples within the table's interpolation error.
#include "abbe/compensate/controller_tables.hpp"

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <map>
#include <sstream>

#include "abbe/identify/workspace_map.hpp"
#include "abbe/io/input_error.hpp"
#include "abbe/machine/machine.hpp"
#include "abbe/pipeline/model_set.hpp"
#include "abbe/pipeline/predict.hpp"

namespace abbe::compensate {
namespace {

using machine::Axis;
using model::ModelKind;

const std::string kSample = std::string(ABBE_SOURCE_DIR) + "/machines/sample/machine.yaml";
const std::string kZero = std::string(ABBE_TEST_DATA_DIR) + "/compensate/zero.yaml";
const std::string kExx = std::string(ABBE_TEST_DATA_DIR) + "/export/exx-only.yaml";
const std::vector<std::string> kFiles = {
    "drilling.ngc",           "helix-g18-g19.ngc",     "inch-r-arcs.ngc",      "spline-slot.ngc",
    "spline-slot-corner.ngc", "thesis-toolpath-1.ngc", "thesis-toolpath-2.ngc"};

// The points of every nc-sample (path pipeline, the machine's setup).
std::vector<model::EvalPoint> sample_points(const machine::Machine& m) {
  std::vector<model::EvalPoint> out;
  for (const std::string& f : kFiles) {
    std::ifstream in(std::string(ABBE_SOURCE_DIR) + "/nc-samples/" + f, std::ios::binary);
    EXPECT_TRUE(in) << f;
    pipeline::PredictOptions po;
    pipeline::predict(in, f, m, po,
                      [&](const model::EvalPoint& p, std::size_t, const pipeline::ModelSet&) {
                        out.push_back(p);
                      });
  }
  return out;
}

// The deviation the models predict at p (µm), and what is left of it once
// each joint's table has added its correction at that joint's position.
struct TableResidual {
  Eigen::Vector3d before;
  Eigen::Vector3d after;
};
TableResidual residual_after_tables(pipeline::ModelSet& models, const model::EvalPoint& p,
                                    const std::array<JointTable, 3>& tables) {
  models.evaluate(p, "sample", 0);
  TableResidual r;
  r.before = models.deviations()[0].e_um;
  const Eigen::Vector3d s = p.p + Eigen::Vector3d(0.0, 0.0, p.tool_length);
  r.after = r.before;
  for (std::size_t j = 0; j < 3; ++j)
    r.after[static_cast<Eigen::Index>(j)] +=
        tables[j].correction_um(s[static_cast<Eigen::Index>(j)], p.dir[j]);
  return r;
}

bool inside_travel(const machine::Machine& m, const model::EvalPoint& p) {
  const Eigen::Vector3d s = p.p + Eigen::Vector3d(0.0, 0.0, p.tool_length);
  for (Axis a : machine::kAxes)
    if (s[machine::index(a)] < m.travel(a).min || s[machine::index(a)] > m.travel(a).max)
      return false;
  return true;
}

// The lines of a COMP_FILE checked as LinuxCNC reads them (its documented
// behaviour: each line scanned with "%lf %lf %lf", the first line that does
// not give three numbers ends the table), plus: nothing else on a line,
// nominal strictly increasing, at most 256 entries — so every line of the
// file is read.
void expect_linuxcnc_rules(const std::string& text) {
  std::istringstream in(text);
  std::string line;
  std::size_t n = 0;
  double last = -HUGE_VAL;
  while (std::getline(in, line)) {
    ++n;
    double v[3];
    int used = 0;
    ASSERT_EQ(std::sscanf(line.c_str(), "%lf %lf %lf%n", &v[0], &v[1], &v[2], &used), 3)
        << "line " << n << ": " << line;
    EXPECT_EQ(static_cast<std::size_t>(used), line.size())
        << "line " << n << " has more than three columns: " << line;
    for (double x : v) EXPECT_TRUE(std::isfinite(x)) << line;
    EXPECT_GT(v[0], last) << "line " << n << ": positions must increase";
    last = v[0];
  }
  EXPECT_GE(n, 2u);
  EXPECT_LE(n, kLinuxCncMaxEntries);
  EXPECT_EQ(text.back(), '\n');
}

TEST(RegularPositions, EndsExactSpacingAtMostStep) {
  const auto v = regular_positions(-990.0, 0.0, 25.0, 0, 1000, "--step");
  ASSERT_EQ(v.size(), 41u);  // 990/25 = 39.6 → 40 intervals of 24.75 mm
  EXPECT_EQ(v.front(), -990.0);
  EXPECT_EQ(v.back(), 0.0);
  EXPECT_NEAR(v[1] - v[0], 24.75, 1e-12);
  EXPECT_EQ(regular_positions(-500.0, 0.0, 25.0, 0, 1000, "--step").size(), 21u);
  EXPECT_EQ(regular_positions(-500.0, 0.0, 0.0, 6, 1000, "--count").size(), 6u);
  EXPECT_EQ(regular_positions(-500.0, 0.0, 1e6, 0, 1000, "--step").size(), 2u);
}

TEST(RegularPositions, BadStepsAreInputErrors) {
  for (double step : {0.0, -1.0, std::nan(""), HUGE_VAL, 1e-9})
    EXPECT_THROW(regular_positions(-990.0, 0.0, step, 0, 256, "--step"), InputError) << step;
  EXPECT_THROW(regular_positions(-990.0, 0.0, 0.0, 1, 256, "--count"), InputError);
  EXPECT_THROW(regular_positions(-990.0, 0.0, 0.0, 300, 256, "--count"), InputError);
  try {
    regular_positions(-990.0, 0.0, 1.0, 0, kLinuxCncMaxEntries, "--step");
    FAIL() << "991 entries accepted";
  } catch (const InputError& e) {
    EXPECT_EQ(e.where().field, "--step");
    EXPECT_NE(e.message().find("at most 256"), std::string::npos) << e.message();
  }
}

TEST(ControllerTables, ZeroMachineGivesZeroTables) {
  const machine::Machine m = machine::Machine::load(kZero);
  for (ModelKind k : {ModelKind::htm, ModelKind::ae_arm, ModelKind::dual})
    for (double L : {0.0, 130.0, 200.0})
      for (const Eigen::Vector3d& at :
           {Eigen::Vector3d(-495.0, -250.0, -360.0), Eigen::Vector3d(0.0, 0.0, -L),
            Eigen::Vector3d(-990.0, -500.0, -460.0 - L)}) {
        JointTableOptions o;
        o.model = k;
        o.tool_length = L;
        o.at_tip = at;
        for (const JointTable& t : joint_tables(m, o)) {
          EXPECT_FALSE(t.direction_dependent());
          for (std::size_t i = 0; i < t.nominal_mm.size(); ++i) {
            EXPECT_EQ(t.forward_um[i], 0.0);
            EXPECT_EQ(t.reverse_um[i], 0.0);
          }
          const std::string text = linuxcnc_comp_text(t);
          expect_linuxcnc_rules(text);
          std::istringstream in(text);
          std::string a, b, c;
          while (in >> a >> b >> c) EXPECT_TRUE(b == "0" && c == "0") << b << " " << c;
        }
      }
  GridOptions g;
  g.models = {ModelKind::htm, ModelKind::ae_arm, ModelKind::dual};
  g.step.setConstant(100.0);
  g.tool_length = 200.0;
  const VolumetricGrid grid = volumetric_grid(m, g);
  for (const auto& dev : grid.deviation_um)
    for (const auto& e : dev) EXPECT_EQ(e, Eigen::Vector3d::Zero());
}

// EXX only: fwd 0, 10, 4 and rev −2, 8, 3 µm at X −990, −495, 0 (exx-only.csv).
TEST(ControllerTables, HandComputedLinuxCncFile) {
  const machine::Machine m = machine::Machine::load(kExx);
  JointTableOptions o;
  o.tool_length = 130.0;
  o.at_tip = Eigen::Vector3d(-100.0, -100.0, -300.0);
  const auto tables = joint_tables(m, o);
  const JointTable& x = tables[0];
  ASSERT_EQ(x.nominal_mm.size(), 199u);  // 990 mm in 5 mm steps
  EXPECT_TRUE(x.direction_dependent());
  const std::string text = linuxcnc_comp_text(x);
  expect_linuxcnc_rules(text);
  EXPECT_EQ(text.substr(0, text.find('\n')), "-990 0 0.002");
  EXPECT_NE(text.find("\n-495 -0.01 -0.008\n"), std::string::npos);
  // Between the table's points: −745 is 245 mm past −990, 10·245/495 µm fwd.
  EXPECT_NE(text.find(fmt::format("\n-745 {:.6f} {:.6f}\n", -0.01 * 245.0 / 495.0,
                                  -(-2.0 + 10.0 * 245.0 / 495.0) * 1e-3)),
            std::string::npos)
      << text;
  EXPECT_EQ(text.substr(text.rfind('\n', text.size() - 2) + 1), "0 -0.004 -0.003\n");
  // In inch (LINEAR_UNITS = inch): −990/25.4 and 0.002/25.4.
  const std::string inch = linuxcnc_comp_text(x, true);
  expect_linuxcnc_rules(inch);
  EXPECT_EQ(inch.substr(0, inch.find('\n')), "-38.976378 0 0.000079");
  // Y and Z have no errors: all-zero files.
  for (int a : {1, 2}) {
    EXPECT_FALSE(tables[static_cast<std::size_t>(a)].direction_dependent());
    for (double v : tables[static_cast<std::size_t>(a)].forward_um) EXPECT_EQ(v, 0.0);
  }
  // The INI lines name the type and the files.
  const std::string ini = linuxcnc_ini_text(m, o, tables);
  EXPECT_NE(ini.find("[JOINT_0]\nCOMP_FILE = x.comp\nCOMP_FILE_TYPE = 1\n"), std::string::npos);
  EXPECT_NE(ini.find("[JOINT_2]\nCOMP_FILE = z.comp\nCOMP_FILE_TYPE = 1\n"), std::string::npos);
  EXPECT_NE(ini.find("# X: 199 entries, forward and reverse differ"), std::string::npos) << ini;
  EXPECT_NE(ini.find("# Y: 101 entries, forward = reverse"), std::string::npos) << ini;
}

// With EXX only the X table corrects every point of the samples, wherever Y
// and Z stand and in both directions (its nodes hold EXX's breakpoints, so
// the interpolation is exact).
TEST(ControllerTables, ExxOnlyTableCorrectsTheSamples) {
  const machine::Machine m = machine::Machine::load(kExx);
  JointTableOptions o;
  o.tool_length = 130.0;
  o.at_tip = travel_centre_tip(m, o.tool_length);
  EXPECT_EQ(o.at_tip, Eigen::Vector3d(-495.0, -250.0, -360.0));
  const auto tables = joint_tables(m, o);
  pipeline::ModelSet models(m, {ModelKind::ae_arm});
  std::size_t n = 0;
  double largest = 0.0;
  for (const model::EvalPoint& p : sample_points(m)) {
    const TableResidual r = residual_after_tables(models, p, tables);
    if (p.dir[0] == 0) continue;  // at rest LinuxCNC keeps the last trim: not a table value
    largest = std::max(largest, r.before.norm());
    EXPECT_LT(r.after.norm(), 1e-9) << p.p.transpose();
    ++n;
  }
  EXPECT_GT(n, 1000u);
  EXPECT_GT(largest, 1.0);  // the samples do see the error
}

// Sample machine: along each joint's line the table leaves at most the
// interpolation error of the table, measured on a check grid ten times finer
// than the table (0.5 mm). The default 5 mm entries hold every breakpoint
// of the sample's component tables (25 mm apart from the lower end of the
// travel, a last one at 0), and along one joint every model is linear
// between them up to round-off, so that error is below 1e-6 µm; compared is the component along the
// joint with the other axes where the table was made (a per-joint table corrects only that:
// docs/export.md).
TEST(ControllerTables, SampleMachineJointTablesWithinInterpolationError) {
  const machine::Machine m = machine::Machine::load(kSample);
  const auto points = sample_points(m);
  for (ModelKind k : {ModelKind::htm, ModelKind::ae_arm, ModelKind::dual}) {
    JointTableOptions o;
    o.model = k;
    o.tool_length = 130.0;
    o.at_tip = Eigen::Vector3d(-495.0, -250.0, -410.0);
    const auto tables = joint_tables(m, o);
    pipeline::ModelSet models(m, {k});
    const Eigen::Vector3d at_axes = o.at_tip + Eigen::Vector3d(0.0, 0.0, o.tool_length);
    // The error along the line of joint j at axis position s, direction dir.
    auto on_line = [&](std::size_t j, double s, int dir) {
      model::EvalPoint p;
      Eigen::Vector3d axes = at_axes;
      axes[static_cast<Eigen::Index>(j)] = s;
      p.p = axes - Eigen::Vector3d(0.0, 0.0, o.tool_length);
      p.tool_length = o.tool_length;
      p.dir[j] = static_cast<std::int8_t>(dir);
      models.evaluate(p, "line", 0);
      return models.deviations()[0].e_um[static_cast<Eigen::Index>(j)];
    };
    for (std::size_t j = 0; j < 3; ++j) {
      const JointTable& t = tables[j];
      expect_linuxcnc_rules(linuxcnc_comp_text(t));
      EXPECT_TRUE(t.direction_dependent()) << "the sample's tables are bidirectional";
      const double lo = t.nominal_mm.front(), hi = t.nominal_mm.back();
      double bound = 0.0;
      for (double s = lo; s <= hi; s += 0.5)
        for (int dir : {1, -1})
          bound = std::max(bound, std::abs(on_line(j, s, dir) + t.correction_um(s, dir)));
      double worst = 0.0;
      std::size_t n = 0;
      for (const model::EvalPoint& p : points) {
        if (p.dir[j] == 0) continue;
        const double s = p.p[static_cast<Eigen::Index>(j)] + (j == 2 ? p.tool_length : 0.0);
        if (s < lo || s > hi) continue;
        worst = std::max(worst, std::abs(on_line(j, s, p.dir[j]) + t.correction_um(s, p.dir[j])));
        ++n;
      }
      EXPECT_GT(n, 100u);
      EXPECT_LE(worst, 1.25 * bound + 1e-6) << model::to_string(k) << " joint " << j;
      EXPECT_LT(bound, 1e-6) << model::to_string(k) << " joint " << j;
      std::printf(
          "[ export ] %s joint %c: %zu sample points, residual max %.2e µm, table "
          "interpolation error %.2e µm\n",
          model::to_string(k), "XYZ"[j], n, worst, bound);
    }
    // For the docs: the whole deviation of the samples (inside the travel)
    // before and after the three tables — what a per-joint table cannot reach.
    double before = 0.0, after = 0.0;
    std::size_t n = 0;
    for (const model::EvalPoint& p : points) {
      if (!inside_travel(m, p)) continue;
      const TableResidual r = residual_after_tables(models, p, tables);
      before += r.before.squaredNorm();
      after += r.after.squaredNorm();
      ++n;
    }
    ASSERT_GT(n, 0u);
    std::printf(
        "[ export ] %s: RMS |d| of %zu sample points %.3f µm, after the three per-joint "
        "tables %.3f µm\n",
        model::to_string(k), n, std::sqrt(before / static_cast<double>(n)),
        std::sqrt(after / static_cast<double>(n)));
  }
}

// The grid at each tool length of the samples, trilinearly interpolated,
// leaves at most the grid's interpolation error at the samples' points
// inside the travel (compared: the deviation with the mean of the
// directions, which is what a grid holds). The interpolation error is
// measured on a check set: per axis the nodes, the cell centres and every
// breakpoint of the machine's component tables (where the tables bend, the
// largest error of a linear interpolation of a piecewise-linear function),
// in every combination; the samples must stay within 1.25 times it.
TEST(ControllerTables, SampleMachineGridWithinInterpolationError) {
  const machine::Machine m = machine::Machine::load(kSample);
  const auto points = sample_points(m);
  std::map<double, std::vector<model::EvalPoint>> by_length;
  for (model::EvalPoint p : points)
    if (inside_travel(m, p)) {
      p.dir = {0, 0, 0};
      by_length[p.tool_length].push_back(p);
    }
  ASSERT_GE(by_length.size(), 1u);
  const std::vector<ModelKind> kinds{ModelKind::htm, ModelKind::ae_arm, ModelKind::dual};
  std::map<double, std::vector<double>> bound_of_step;
  for (double step : {50.0, 25.0}) {
    std::vector<double> worst(3, 0.0), bound(3, 0.0), before2(3, 0.0), after2(3, 0.0);
    std::size_t n = 0;
    for (const auto& [L, pts] : by_length) {
      GridOptions g;
      g.models = kinds;
      g.tool_length = L;
      g.step.setConstant(step);
      const VolumetricGrid grid = volumetric_grid(m, g);
      pipeline::ModelSet models(m, kinds);
      std::array<std::vector<double>, 3> check;
      for (std::size_t a = 0; a < 3; ++a) {
        const auto& v = grid.nodes[a];
        check[a] = v;
        for (std::size_t i = 0; i + 1 < v.size(); ++i) check[a].push_back(0.5 * (v[i] + v[i + 1]));
        for (const machine::ComponentSeries& c : m.table().series())
          if (static_cast<std::size_t>(machine::index(c.id.axis)) == a)
            for (double s : c.position_mm) {
              const double x = s - (a == 2 ? L : 0.0);
              if (x > v.front() && x < v.back()) check[a].push_back(x);
            }
        std::sort(check[a].begin(), check[a].end());
        check[a].erase(std::unique(check[a].begin(), check[a].end()), check[a].end());
      }
      model::EvalPoint q;
      q.tool_length = L;
      for (double z : check[2])
        for (double y : check[1])
          for (double x : check[0]) {
            q.p = Eigen::Vector3d(x, y, z);
            models.evaluate(q, "check", 0);
            for (std::size_t mi = 0; mi < 3; ++mi)
              bound[mi] = std::max(
                  bound[mi], (models.deviations()[mi].e_um - grid.interpolate(mi, q.p)).norm());
          }
      for (const model::EvalPoint& p : pts) {
        models.evaluate(p, "sample", 0);
        for (std::size_t mi = 0; mi < 3; ++mi) {
          const Eigen::Vector3d e = models.deviations()[mi].e_um;
          const double r = (e - grid.interpolate(mi, p.p)).norm();
          worst[mi] = std::max(worst[mi], r);
          before2[mi] += e.squaredNorm();
          after2[mi] += r * r;
        }
        ++n;
      }
    }
    EXPECT_GT(n, 1000u);
    for (std::size_t mi = 0; mi < 3; ++mi) {
      EXPECT_LE(worst[mi], 1.25 * bound[mi] + 1e-6)
          << model::to_string(kinds[mi]) << " step " << step;
      std::printf(
          "[ export ] grid step %g mm, %s: %zu sample points, RMS |d| %.3f µm, after the grid "
          "%.4f µm, residual max %.4f µm, grid interpolation error %.4f µm\n",
          step, model::to_string(kinds[mi]), n, std::sqrt(before2[mi] / static_cast<double>(n)),
          std::sqrt(after2[mi] / static_cast<double>(n)), worst[mi], bound[mi]);
    }
    bound_of_step[step] = bound;
  }
  // A finer grid interpolates better; at 25 mm every model's error is
  // below 1 µm (the samples' deviations reach 40 µm).
  for (std::size_t mi = 0; mi < 3; ++mi) {
    EXPECT_LT(bound_of_step[25.0][mi], bound_of_step[50.0][mi]);
    EXPECT_LT(bound_of_step[25.0][mi], 1.0) << model::to_string(kinds[mi]);
  }
}

// The grid's nodes and deviations are those of `abbe map` at the same spacing.
TEST(ControllerTables, GridMatchesWorkspaceMap) {
  const machine::Machine m = machine::Machine::load(kSample);
  GridOptions g;
  g.models = {ModelKind::htm, ModelKind::ae_arm, ModelKind::dual};
  g.tool_length = 200.0;
  g.step.setConstant(100.0);
  const VolumetricGrid grid = volumetric_grid(m, g);
  identify::MapOptions mo;
  mo.tool_length = 200.0;
  mo.spacing_mm = 100.0;
  mo.models = g.models;
  identify::travel_box(m, mo.tool_length, mo.lo, mo.hi);
  const identify::WorkspaceMap map = identify::compute_map(m, mo);
  ASSERT_EQ(map.points.size(), grid.size());
  EXPECT_EQ(map.xs, grid.nodes[0]);
  EXPECT_EQ(map.zs, grid.nodes[2]);
  for (std::size_t mi = 0; mi < 3; ++mi)
    for (std::size_t i = 0; i < grid.size(); ++i)
      EXPECT_LT((map.deviation_um[mi][i] - grid.deviation_um[mi][i]).norm(), 1e-9);
  // The CSV: header, one row per node, x fastest.
  const std::string csv = grid_csv_text(grid);
  EXPECT_EQ(csv.substr(0, csv.find('\n')),
            "x,y,z,dx_htm,dy_htm,dz_htm,dx_ae_arm,dy_ae_arm,dz_ae_arm,dx_dual,dy_dual,dz_dual");
  EXPECT_EQ(static_cast<std::size_t>(std::count(csv.begin(), csv.end(), '\n')), grid.size() + 1);
  EXPECT_EQ(csv.substr(csv.find('\n') + 1, 14), "-990,-500,-660");
  g.models = {ModelKind::ae_arm};
  const std::string one = grid_csv_text(volumetric_grid(m, g));
  EXPECT_EQ(one.substr(0, one.find('\n')), "x,y,z,dx,dy,dz");
}

TEST(ControllerTables, GridRefusesTooManyNodes) {
  const machine::Machine m = machine::Machine::load(kSample);
  GridOptions g;
  g.step.setConstant(1.0);  // 991 × 501 × 461 nodes
  EXPECT_THROW(volumetric_grid(m, g), InputError);
  g.step = Eigen::Vector3d(25.0, -1.0, 25.0);
  try {
    volumetric_grid(m, g);
    FAIL();
  } catch (const InputError& e) {
    EXPECT_EQ(e.where().field, "--step (Y)");
  }
}

}  // namespace
}  // namespace abbe::compensate
