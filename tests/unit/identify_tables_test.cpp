// Piecewise-linear component tables fitted to a volumetric grid: the fit
// reproduces the data and, written as a component table, predicts a
// held-out grid through the ordinary ErrorModel; the identifiability report
// names what one tool length cannot separate.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "abbe/identify/table_fit.hpp"
#include "abbe/machine/machine.hpp"
#include "abbe/model/error_model.hpp"

namespace abbe::identify {
namespace {

// Box of tool tips and the tool length; s_z = P_z + L.
const Eigen::Vector3d kLo(-600, -400, -500), kHi(-300, -200, -300);
constexpr double kL = 100.0;

// Chain w X' b Y Z t (table X, tool-side Y and Z), smooth random tables with
// knots every 50 mm over the box, reflector points away from the tip.
machine::Machine truth_machine(unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  machine::MachineSpec spec;
  spec.name = "tables";
  spec.file = "<tables>";
  spec.chain = machine::KinematicChain::parse("w X' b Y Z t");
  spec.travel = {machine::Travel{-1000, 0}, machine::Travel{-500, 0}, machine::Travel{-500, 0}};
  spec.tool_length = kL;
  const std::array<Eigen::Vector3d, 3> pts{Eigen::Vector3d(-800, -256, -478),
                                           Eigen::Vector3d(-500, -250, -300),
                                           Eigen::Vector3d(-450, -250, -200)};
  for (int a = 0; a < 3; ++a) {
    auto& r = spec.axes[static_cast<std::size_t>(a)];
    r.present = true;
    r.measured_tip = {-500, -250, -280};
    r.measured_tool_length = kL;
    r.point = {pts[static_cast<std::size_t>(a)], pts[static_cast<std::size_t>(a)],
               pts[static_cast<std::size_t>(a)]};
  }
  std::string csv = "axis,component,position_mm,direction,value\n";
  const Eigen::Vector3d slo = kLo + Eigen::Vector3d(0, 0, kL),
                        shi = kHi + Eigen::Vector3d(0, 0, kL);
  for (int a = 0; a < 3; ++a)
    for (int d = 0; d < 6; ++d) {
      const double amp = d < 3 ? 3.0 : 10.0;  // µm, µrad
      const double c0 = amp * u(rng), c1 = amp * u(rng), c2 = amp * u(rng);
      for (double s = slo[a]; s <= shi[a] + 1e-9; s += 50.0) {
        const double t = (s - slo[a]) / (shi[a] - slo[a]);
        csv +=
            fmt::format("{},{},{},mean,{:.17g}\n", "XYZ"[a],
                        machine::component_name({machine::kAxes[static_cast<std::size_t>(a)], d}),
                        s, c0 + c1 * t + c2 * std::sin(3.0 * t));
      }
    }
  spec.table = machine::ComponentTable::parse(csv, "<tables.csv>");
  return machine::Machine(spec);
}

std::vector<Observation> grid(const model::ErrorModel& m, double step, double shift,
                              double tool_length = kL) {
  std::vector<Observation> obs;
  model::ModelData data;
  // The same axis positions s for any tool length: P_z = s_z − L.
  const double dz = kL - tool_length;
  for (double z = kLo.z() + dz + shift; z <= kHi.z() + dz + 1e-9; z += step)
    for (double y = kLo.y() + shift; y <= kHi.y() + 1e-9; y += step)
      for (double x = kLo.x() + shift; x <= kHi.x() + 1e-9; x += step) {
        Observation o;
        o.point.p = {x, y, z};
        o.point.tool_length = tool_length;
        o.d_um = m.evaluate(o.point, data).e_um;
        obs.push_back(o);
      }
  return obs;
}

const ComponentSeparability& sep(const TableFit& f, const char* name) {
  for (const auto& s : f.separability)
    if (machine::component_name(s.id) == name) return s;
  throw std::runtime_error(name);
}

TEST(IdentifyTables, FitPredictsHeldOutGridThroughTheComponentTable) {
  const machine::Machine truth = truth_machine(11);
  const model::ErrorModel ae(truth, model::ModelKind::ae_arm);
  const ChainExpansion chain(truth);
  TableFitOptions opt;
  opt.knot_spacing_mm = 50.0;
  const TableFit f = fit_component_tables(chain, grid(ae, 25.0, 0.0), opt);
  EXPECT_LT(f.residual_max_um, 1e-6);
  EXPECT_LT(f.fit.rank, f.unknowns);  // one tool length: not everything separates
  EXPECT_FALSE(f.unidentifiable.empty());

  // The fitted table, read back as a component table, predicts a held-out grid.
  machine::MachineSpec spec = truth.spec();
  spec.table = machine::ComponentTable::parse(table_fit_to_csv(f), "<fitted.csv>");
  const machine::Machine fitted(spec);
  const model::ErrorModel fm(fitted, model::ModelKind::ae_arm);
  model::ModelData data;
  double worst = 0.0;
  for (const Observation& o : grid(ae, 50.0, 12.5))
    worst = std::max(worst, (fm.evaluate(o.point, data).e_um - o.d_um).norm());
  EXPECT_LT(worst, 1e-4);  // the CSV keeps 6 significant digits
}

TEST(IdentifyTables, SeparabilityReport) {
  const machine::Machine truth = truth_machine(12);
  const model::ErrorModel ae(truth, model::ModelKind::ae_arm);
  const ChainExpansion chain(truth);
  const TableFit f = fit_component_tables(chain, grid(ae, 25.0, 0.0), {});
  // Every arm of the spindle axis Z is constant over the grid (its carriage
  // moves with all three axes): its angular errors act like its linear
  // errors, every shape of them is ambiguous.
  for (const char* c : {"EAZ", "EBZ", "ECZ", "EYZ"})
    EXPECT_EQ(sep(f, c).null_dims, sep(f, c).knots) << c;
  const auto& w = sep(f, "EAZ").confounded_with;
  EXPECT_NE(std::find(w.begin(), w.end(), "EYZ"), w.end());
  // The reflector of Y sits on the tip's vertical line: the yaw ECY has no
  // arm and is invisible (share 1, nothing to be confounded with).
  EXPECT_NEAR(sep(f, "ECY").null_share, 1.0, 1e-6);
  EXPECT_TRUE(sep(f, "ECY").confounded_with.empty());
  // The roll of the table axis X has the arm z − M_z, which varies on the
  // grid independently of x: only its constant part trades (with straightness
  // slopes); the positioning EXX loses only its constant (offsets add up).
  EXPECT_EQ(sep(f, "EAX").null_dims, 1);
  EXPECT_EQ(sep(f, "EXX").null_dims, 1);
}

// A second tool length changes the z arm of the tool-side axes: the pitch
// and roll of Z (EBZ, EAZ) separate from Z's straightness; the yaw ECZ,
// whose arms lie in x and y, does not.
TEST(IdentifyTables, SecondToolLengthSeparatesPitchAndRollOfZ) {
  const machine::Machine truth = truth_machine(13);
  const model::ErrorModel ae(truth, model::ModelKind::ae_arm);
  const ChainExpansion chain(truth);
  auto data = grid(ae, 50.0, 0.0, kL);
  const auto longer = grid(ae, 50.0, 0.0, kL + 150.0);
  data.insert(data.end(), longer.begin(), longer.end());
  const TableFit f = fit_component_tables(chain, data, {});
  EXPECT_LT(f.residual_max_um, 1e-6);
  EXPECT_LE(sep(f, "EAZ").null_dims, 1);
  EXPECT_LE(sep(f, "EBZ").null_dims, 1);
  EXPECT_EQ(sep(f, "ECZ").null_dims, sep(f, "ECZ").knots);
}

}  // namespace
}  // namespace abbe::identify
