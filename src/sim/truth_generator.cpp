#include "abbe/sim/truth_generator.hpp"

#include <Eigen/Geometry>  // cross()
#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "abbe/io/units.hpp"
#include "abbe/sim/laser_campaign.hpp"
#include "abbe/sim/random.hpp"

namespace abbe::sim {

namespace {

constexpr double kScrewPitchMm = 10.0;      // ballscrew pitch of every axis
constexpr double kScrewAmplitudeUm = 0.25;  // ballscrew cycle on the positioning component
// The magnitudes are calibrated on a fixed 25 mm grid, so a seed gives the same
// machine whatever the campaign spacing.
constexpr double kCalibrationSpacingMm = 25.0;

// Target magnitudes of one component, as an ISO 230-2 evaluation reports them.
struct ComponentTarget {
  double mean_deviation;  // M: peak-to-peak of the bidirectional mean (µm, µrad)
  double mean_reversal;   // mean of B_i
  double max_reversal;    // B = max |B_i| (≥ |mean_reversal|)
  double repeatability;   // R
};

// The thesis' Tables 4–6 (angular values converted from µm/mm to µrad). Rolls
// (EAX, EBY, ECZ) are not in the thesis; their values are our choice.
// Order per axis: EX EY EZ EA EB EC.
const ComponentTarget kMazak[3][6] = {
    {{14.620, 2.367, 2.720, 4.566},
     {5.62, 0.16, 0.16, 3.92},
     {4.51, 0.82, 0.82, 8.88},
     {8.0, 0.0, 0.0, 2.0},
     {16.7, 0.0, 3.1, 5.7},
     {9.7, 0.5, 1.0, 5.0}},
    {{3.04, 0.06, 0.06, 19.82},
     {16.170, 2.909, 3.440, 5.174},
     {2.45, 0.25, 0.25, 3.85},
     {25.0, 0.2, 0.9, 15.3},
     {8.0, 0.0, 0.0, 2.0},
     {21.2, -2.1, 3.8, 29.8}},
    {{1.25, -0.44, 0.44, 13.82},
     {0.72, -0.10, 0.10, 1.45},
     {6.090, 15.553, 15.553, 16.135},
     {12.9, -0.7, 1.4, 13.3},
     {25.9, -1.6, 3.7, 31.4},
     {5.0, 0.0, 0.0, 2.0}},
};

ComponentTarget generic_target(Random& rng, int j, int c) {
  ComponentTarget t{};
  if (c == j) {
    t.mean_deviation = rng.uniform(5.0, 20.0);
    t.mean_reversal = rng.uniform(1.0, 5.0);
  } else if (c < 3) {
    t.mean_deviation = rng.uniform(2.0, 8.0);
    t.mean_reversal = rng.uniform(-0.5, 0.5);
  } else if (c - 3 == j) {
    t.mean_deviation = rng.uniform(3.0, 10.0);
    t.mean_reversal = rng.uniform(-0.5, 0.5);
  } else {
    t.mean_deviation = rng.uniform(5.0, 25.0);
    t.mean_reversal = rng.uniform(-1.0, 1.0);
  }
  t.max_reversal = std::abs(t.mean_reversal) * rng.uniform(1.0, 1.3);
  t.repeatability = 0.0;  // generic: noise from the uncertainty budget
  return t;
}

// Reading noise (one standard deviation) from the thesis' uncertainty budget.
double budget_sigma(int j, int c) {
  if (c == j) return 0.3;  // positioning, µm
  if (c < 3) return 0.67;  // straightness, µm (u_DEVICE of the thesis' Table 9)
  return 0.3;              // angular, µrad (±0.5 µm/m device accuracy, rectangular)
}

// Random smooth shape with unit-ish size: cubic polynomial + two long waves.
ErrorComponent random_shape(Random& rng, const AxisTruth& axis) {
  ErrorComponent e;
  e.centre = 0.5 * (axis.travel_min + axis.travel_max);
  e.half_range = 0.5 * (axis.travel_max - axis.travel_min);
  const double length = axis.travel_max - axis.travel_min;
  e.poly = {0.3 * rng.normal(), rng.normal(), 0.7 * rng.normal(), 0.5 * rng.normal()};
  for (int m = 0; m < 2; ++m)
    e.waves.push_back(
        {rng.uniform(0.1, 0.3), length * rng.uniform(0.3, 1.2), rng.uniform(0.0, units::kTwoPi)});
  return e;
}

// dst += f·src (same centre and half_range).
void add_scaled(ErrorComponent& dst, const ErrorComponent& src, double f) {
  if (f == 0.0) return;
  if (dst.poly.size() < src.poly.size()) dst.poly.resize(src.poly.size(), 0.0);
  for (std::size_t n = 0; n < src.poly.size(); ++n) dst.poly[n] += f * src.poly[n];
  for (const Wave& w : src.waves) dst.waves.push_back({f * w.amplitude, w.wavelength, w.phase});
  dst.reversal += f * src.reversal;
  dst.reversal_slope += f * src.reversal_slope;
}

void scale_shape(ErrorComponent& e, double a) {
  for (double& c : e.poly) c *= a;
  for (Wave& w : e.waves) w.amplitude *= a;
}

double peak_to_peak(const std::vector<double>& v) {
  const auto [lo, hi] = std::minmax_element(v.begin(), v.end());
  return *hi - *lo;
}

// Peak-to-peak over the targets of the noise-free mean reading of component c of axis j.
double reading_p2p(const TruthMachine& truth, const CampaignSetup& campaign, int j, int c,
                   const std::vector<double>& targets) {
  const AxisRecord& rec = campaign.axes[static_cast<std::size_t>(j)];
  const Eigen::Vector3d s_meas = TruthMachine::axis_positions(rec.measured_at, rec.tool_length);
  std::vector<double> values;
  for (double target : targets) {
    Eigen::Vector3d s = s_meas;
    s[j] = target;
    Eigen::Vector3d m = rec.point;
    for (int i = 0; i < 3; ++i)
      if (truth.chain.moves(j, i)) m[i] += s[i] - s_meas[i];
    double v = 0.0;
    if (c < 3) {
      v = 0.5 * (truth.laser_linear_reading_um(j, s, +1, m)[c] +
                 truth.laser_linear_reading_um(j, s, -1, m)[c]);
    } else {
      v = truth.axes[static_cast<std::size_t>(j)].components[static_cast<std::size_t>(c)].base(
          target);
    }
    values.push_back(v);
  }
  return peak_to_peak(values);
}

void set_geometry(GeneratedMachine& g, const std::string& chain) {
  TruthMachine& t = g.truth;
  t.chain = ChainLayout::parse(chain);
  const double travel[3] = {990.0, 500.0, 460.0};
  for (int j = 0; j < 3; ++j) {
    t.axes[static_cast<std::size_t>(j)].travel_min = -travel[j];
    t.axes[static_cast<std::size_t>(j)].travel_max = 0.0;
  }
  t.tool_length = 130.0;
  t.tool_table = {{1, 200.0}};
  // Pivots (points of each carriage, positions with all axes at 0): for
  // `w X' b Y Z t` the table centre under its surface, the centre of the Y
  // carriage and of the Z ram above the spindle nose. Other chains: workpiece-
  // side carriages under the table, tool-side ones stacked above the spindle.
  int tool_side_rank = 0, workpiece_side_rank = 0;  // counted from the bed outwards
  for (int k = 2; k >= 0; --k) {
    const int j = t.chain.order()[static_cast<std::size_t>(k)];
    AxisTruth& a = t.axes[static_cast<std::size_t>(j)];
    if (t.chain.workpiece_side(j)) {
      a.pivot0 = Eigen::Vector3d(-495.0, -250.0, -600.0 - 100.0 * workpiece_side_rank);
      ++workpiece_side_rank;
    } else {
      a.pivot0 = Eigen::Vector3d(0.0, 0.0, 450.0 - 200.0 * tool_side_rank);
      ++tool_side_rank;
    }
  }
  // Measurement record after the thesis' section 4.1.2 (docs/virtual-machine.md).
  auto& a = g.campaign.axes;
  a[0].measured_at = Eigen::Vector3d(-495.0, -256.0, -280.0);
  a[0].tool_length = 198.0;
  a[0].point = Eigen::Vector3d(-800.0, -256.0, -478.0);
  a[1].measured_at = Eigen::Vector3d(-500.0, -250.0, -280.0);
  a[1].tool_length = 220.0;
  a[1].point = Eigen::Vector3d(-500.0, -250.0, -280.0);
  a[2].measured_at = Eigen::Vector3d(-495.0, -250.0, -200.0);
  a[2].tool_length = 130.0;
  a[2].point = Eigen::Vector3d(-495.0, -250.0, -200.0);
}

}  // namespace

GeneratedMachine generate_machine(const GeneratorOptions& options) {
  const bool mazak = options.profile == "mazak";
  if (!mazak && options.profile != "generic")
    throw std::invalid_argument("unknown machine profile \"" + options.profile +
                                "\" (mazak or generic)");
  if (!(options.spacing_mm > 0.0)) throw std::invalid_argument("target spacing must be > 0 mm");
  if (options.runs < 2) throw std::invalid_argument("a campaign needs at least 2 runs");
  if (options.squareness_sigma_urad &&
      !(std::isfinite(*options.squareness_sigma_urad) && *options.squareness_sigma_urad >= 0.0))
    throw std::invalid_argument("squareness sigma must be a finite number ≥ 0 µrad");
  Random rng(options.seed);
  GeneratedMachine g;
  set_geometry(g, options.chain);
  g.truth.name = mazak ? "sample machine (SYNTHETIC, shaped after a Mazak AJV 25-405)"
                       : "virtual machine (SYNTHETIC, generic profile)";
  g.campaign.seed = rng.next_seed();
  g.campaign.spacing_mm = options.spacing_mm;
  g.campaign.runs = options.runs;
  // The mazak profile carries the thesis' squareness over as the result of
  // its own (separate) measurement: no simulated noise on top by default.
  g.campaign.squareness_sigma_urad =
      options.squareness_sigma_urad.value_or(mazak ? 0.0 : 2.0 * options.noise_scale);
  if (mazak) {
    g.truth.squareness = {14.569, -24.362, 13.757};
  } else {
    g.truth.squareness = {rng.uniform(-20.0, 20.0), rng.uniform(-20.0, 20.0),
                          rng.uniform(-20.0, 20.0)};
  }

  ComponentTarget targets[3][6];
  for (int j = 0; j < 3; ++j)
    for (int c = 0; c < 6; ++c) targets[j][c] = mazak ? kMazak[j][c] : generic_target(rng, j, c);

  // Shapes and reversal; angular components first (their readings are direct).
  for (int j = 0; j < 3; ++j) {
    AxisTruth& axis = g.truth.axes[static_cast<std::size_t>(j)];
    for (int c = 0; c < 6; ++c) {
      const ComponentTarget& tg = targets[j][c];
      ErrorComponent e = random_shape(rng, axis);
      e.reversal = tg.mean_reversal;
      const double extra = std::max(0.0, tg.max_reversal - std::abs(tg.mean_reversal));
      e.reversal_slope = rng.sign() * 0.6 * extra;
      axis.components[static_cast<std::size_t>(c)] = e;
      double sigma = budget_sigma(j, c);
      if (mazak) {
        const double b = std::max(tg.max_reversal, std::abs(tg.mean_reversal));
        sigma = std::clamp((tg.repeatability - b) / 6.0, 0.05, 0.15 * tg.mean_deviation);
      }
      g.campaign.axes[static_cast<std::size_t>(j)].sigma[static_cast<std::size_t>(c)] =
          sigma * options.noise_scale;
    }
  }
  // Calibrate each shape so the noise-free campaign shows the target mean deviation M.
  for (int pass = 0; pass < 2; ++pass) {
    for (int j = 0; j < 3; ++j) {
      const auto tgt =
          campaign_targets(g.truth.axes[static_cast<std::size_t>(j)], kCalibrationSpacingMm);
      for (int c = (pass == 0 ? 3 : 0); c < (pass == 0 ? 6 : 3); ++c) {
        ErrorComponent& e =
            g.truth.axes[static_cast<std::size_t>(j)].components[static_cast<std::size_t>(c)];
        const double want = targets[j][c].mean_deviation;
        const ErrorComponent random_part = e;
        ErrorComponent fixed;  // terms not scaled by the calibration
        fixed.centre = e.centre;
        fixed.half_range = e.half_range;
        fixed.reversal = e.reversal;
        fixed.reversal_slope = e.reversal_slope;
        if (c < 3) {
          // The reading contains the Abbe term (θ × (M − C))_c of the angular
          // motions (M − C is constant: both move with U(j)). Where it alone
          // exceeds half the target, a fraction of it is cancelled in t_c
          // (correlated guideway errors), so the reading can match the target.
          e = fixed;
          const double abbe = reading_p2p(g.truth, g.campaign, j, c, tgt);
          if (abbe > 0.5 * want) {
            const double cancel = 1.0 - 0.5 * want / abbe;
            const AxisRecord& rec = g.campaign.axes[static_cast<std::size_t>(j)];
            const Eigen::Vector3d d =
                rec.point -
                g.truth.pivot(j, TruthMachine::axis_positions(rec.measured_at, rec.tool_length));
            const auto& comps = g.truth.axes[static_cast<std::size_t>(j)].components;
            for (int m = 0; m < 3; ++m) {
              // (θ × D)_c = Σ_m θ_m·(e_m × D)_c, µrad·mm in µm.
              const double f = Eigen::Vector3d::Unit(m).cross(d)[c] * units::kUmPerUradMm;
              add_scaled(fixed, comps[static_cast<std::size_t>(3 + m)], -cancel * f);
            }
          }
        }
        // e = a·random_part + fixed; p2p(a) is convex in a: bisect for p2p(a) = want, a ≥ 0.
        auto set_factor = [&](double a) {
          e = random_part;
          scale_shape(e, a);
          e.reversal = e.reversal_slope = 0.0;
          add_scaled(e, fixed, 1.0);
        };
        auto p2p_at = [&](double a) {
          set_factor(a);
          return reading_p2p(g.truth, g.campaign, j, c, tgt);
        };
        double hi = 1.0;
        while (p2p_at(hi) < want && hi < 1e6) hi *= 2.0;
        double lo = 0.0;
        if (p2p_at(0.0) >= want) {
          hi = 0.0;  // the fixed part alone already reaches the target
        } else {
          for (int it = 0; it < 50; ++it) {
            const double mid = 0.5 * (lo + hi);
            (p2p_at(mid) < want ? lo : hi) = mid;
          }
        }
        set_factor(hi);
      }
    }
  }
  // The ballscrew cycle (not scaled by the calibration).
  for (int j = 0; j < 3; ++j)
    g.truth.axes[static_cast<std::size_t>(j)]
        .components[static_cast<std::size_t>(j)]
        .waves.push_back({kScrewAmplitudeUm, kScrewPitchMm, rng.uniform(0.0, units::kTwoPi)});
  if (options.angular_scale != 1.0)
    for (auto& axis : g.truth.axes)
      for (int c = 3; c < 6; ++c) {
        ErrorComponent& e = axis.components[static_cast<std::size_t>(c)];
        scale_shape(e, options.angular_scale);
        e.reversal *= options.angular_scale;
        e.reversal_slope *= options.angular_scale;
      }
  return g;
}

}  // namespace abbe::sim
