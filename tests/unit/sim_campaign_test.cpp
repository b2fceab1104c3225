// The virtual laser campaign and the truth file: targets, readings equal the
// truth at the reflector point, noise statistics, determinism, exact YAML
// round trip, clear errors for bad truth files.
#include <gtest/gtest.h>
#include <yaml-cpp/yaml.h>

#include <Eigen/Geometry>  // cross()
#include <array>
#include <cmath>
#include <sstream>

#include "abbe/io/input_error.hpp"
#include "abbe/sim/laser_campaign.hpp"
#include "abbe/sim/truth_file.hpp"
#include "abbe/sim/validation_measurement.hpp"

namespace abbe::sim {
namespace {

GeneratedMachine small_machine(double noise_scale, std::uint64_t seed = 11) {
  GeneratorOptions o;
  o.seed = seed;
  o.noise_scale = noise_scale;
  o.spacing_mm = 50.0;
  return generate_machine(o);
}

TEST(SimCampaign, TargetsCoverTheTravel) {
  AxisTruth a;
  a.travel_min = -990.0;
  a.travel_max = 0.0;
  const auto t = campaign_targets(a, 25.0);
  ASSERT_EQ(t.size(), 41u);
  EXPECT_DOUBLE_EQ(t.front(), -990.0);
  EXPECT_DOUBLE_EQ(t[39], -15.0);
  EXPECT_DOUBLE_EQ(t.back(), 0.0);
  a.travel_min = -500.0;
  EXPECT_EQ(campaign_targets(a, 25.0).size(), 21u);
}

// Without noise every reading is [E_j(M) − M]_k at the moved reflector, and
// the table's fwd/rev are those readings for the two directions.
TEST(SimCampaign, NoiseFreeReadingsAreTheTruthAtTheReflector) {
  const GeneratedMachine g = small_machine(0.0);
  const CampaignResult r = run_campaign(g);
  EXPECT_EQ(r.runs.size(), 6u * 2u * 5u * (21u + 11u + 11u));
  const TruthMachine& t = g.truth;
  int checked = 0;
  for (const TableEntry& e : r.table) {
    const AxisRecord& rec = g.campaign.axes[static_cast<std::size_t>(e.axis)];
    Eigen::Vector3d s = TruthMachine::axis_positions(rec.measured_at, rec.tool_length);
    const Eigen::Vector3d s_meas = s;
    s[e.axis] = e.position_mm;
    Eigen::Vector3d m = rec.point;
    if (t.chain.moves(e.axis, e.axis)) m[e.axis] += s[e.axis] - s_meas[e.axis];
    for (int dir : {+1, -1}) {
      const double want = e.component < 3
                              ? t.laser_linear_reading_um(e.axis, s, dir, m)[e.component]
                              : t.rotation_urad(e.axis, e.position_mm, dir)[e.component - 3];
      EXPECT_NEAR(dir > 0 ? e.fwd : e.rev, want, 1e-12);
      ++checked;
    }
  }
  EXPECT_EQ(checked, 2 * 6 * (21 + 11 + 11));
  EXPECT_DOUBLE_EQ(r.squareness.ec0y, 14.569);
}

// The spindle axis Z, measured with the optic at the tool tip (M = P while
// measured): with only Z's errors the truth at the tip, moved with Z, equals
// the laser reading — the reading contains the Abbe term from the pivot.
TEST(SimCampaign, ToolSideReadingEqualsTipDeviationAtTheOptic) {
  GeneratedMachine g = small_machine(0.0);
  for (int j = 0; j < 2; ++j)
    for (auto& c : g.truth.axes[static_cast<std::size_t>(j)].components) c = ErrorComponent{};
  g.truth.squareness = {};
  const AxisRecord& rec = g.campaign.axes[2];
  ASSERT_EQ(rec.point, rec.measured_at);
  const CampaignResult r = run_campaign(g);
  int checked = 0;
  for (const TableEntry& e : r.table) {
    if (e.axis != 2 || e.component > 2) continue;
    TipState tip;
    tip.p = rec.measured_at;
    tip.p.z() = e.position_mm - rec.tool_length;  // s_z = target
    tip.tool_length = rec.tool_length;
    tip.dir = {0, 0, -1};
    EXPECT_NEAR(e.rev, g.truth.deviation_um(tip)[e.component], 1e-12);
    ++checked;
  }
  EXPECT_EQ(checked, 3 * 11);
  // Far from the optic the tip sees an extra θ × arm.
  TipState far;
  far.p = rec.measured_at + Eigen::Vector3d(0.0, 0.0, -150.0);
  far.tool_length = rec.tool_length + 150.0;
  const Eigen::Vector3d s = TruthMachine::axis_positions(far.p, far.tool_length);
  const Eigen::Vector3d at_optic = g.truth.laser_linear_reading_um(2, s, 0, rec.measured_at);
  const Eigen::Vector3d theta = g.truth.rotation_urad(2, s.z(), 0);
  EXPECT_NEAR(
      (g.truth.deviation_um(far) - at_optic - 1e-3 * theta.cross(far.p - rec.measured_at)).norm(),
      0.0, 1e-3);  // second order: θ²·arm
}

TEST(SimCampaign, NoiseHasTheConfiguredSize) {
  const GeneratedMachine noisy = small_machine(1.0);
  const GeneratedMachine clean = [&] {
    GeneratedMachine c = noisy;
    for (auto& a : c.campaign.axes) a.sigma.fill(0.0);
    c.campaign.squareness_sigma_urad = 0.0;
    return c;
  }();
  const CampaignResult a = run_campaign(noisy), b = run_campaign(clean);
  ASSERT_EQ(a.runs.size(), b.runs.size());
  // Y, EBY: residual standard deviation vs the configured sigma.
  double sum = 0.0, sum2 = 0.0;
  int n = 0;
  for (std::size_t i = 0; i < a.runs.size(); ++i) {
    if (a.runs[i].axis != 1 || a.runs[i].component != 4) continue;
    const double r = a.runs[i].deviation - b.runs[i].deviation;
    sum += r;
    sum2 += r * r;
    ++n;
  }
  const double sigma = noisy.campaign.axes[1].sigma[4];
  ASSERT_GT(sigma, 0.0);
  const double mean = sum / n, sd = std::sqrt(sum2 / n - mean * mean);
  EXPECT_NEAR(sd, sigma, 0.15 * sigma) << n;
  EXPECT_NEAR(mean, 0.0, 4.0 * sigma / std::sqrt(n));
}

// Squareness is "measured" separately (docs/virtual-machine.md): the truth
// plus the squareness noise, nothing else. With large angular errors and no
// noise it is the truth exactly (no contamination by angular errors, arms or
// straightness slopes); with noise (generic profile: 2 µrad), the error over
// many campaigns has mean 0 and the configured standard deviation.
TEST(SimCampaign, SquarenessMeasurementIsUnbiased) {
  GeneratorOptions o;
  o.seed = 7;
  o.spacing_mm = 50.0;
  o.angular_scale = 50.0;  // ≈ 1 mrad tilts
  o.noise_scale = 0.0;
  const GeneratedMachine steep = generate_machine(o);
  const CampaignResult exact = run_campaign(steep);
  EXPECT_EQ(exact.squareness.ec0y, steep.truth.squareness.ec0y);
  EXPECT_EQ(exact.squareness.eb0z, steep.truth.squareness.eb0z);
  EXPECT_EQ(exact.squareness.ea0z, steep.truth.squareness.ea0z);

  GeneratorOptions go;
  go.seed = 7;
  go.profile = "generic";
  go.spacing_mm = 50.0;
  GeneratedMachine g = generate_machine(go);
  const double sigma = g.campaign.squareness_sigma_urad;
  ASSERT_EQ(sigma, 2.0);
  const int n = 300;
  std::array<double, 3> sum{}, sum2{};
  for (int k = 0; k < n; ++k) {
    g.campaign.seed = 1000 + static_cast<std::uint64_t>(k);
    const Squareness m = run_campaign(g).squareness;
    const std::array<double, 3> d{m.ec0y - g.truth.squareness.ec0y,
                                  m.eb0z - g.truth.squareness.eb0z,
                                  m.ea0z - g.truth.squareness.ea0z};
    for (std::size_t c = 0; c < 3; ++c) {
      sum[c] += d[c];
      sum2[c] += d[c] * d[c];
    }
  }
  for (std::size_t c = 0; c < 3; ++c) {
    const double mean = sum[c] / n, sd = std::sqrt(sum2[c] / n - mean * mean);
    EXPECT_NEAR(mean, 0.0, 4.0 * sigma / std::sqrt(n)) << c;
    EXPECT_NEAR(sd, sigma, 0.15 * sigma) << c;
  }
}

// Default squareness noise per profile: mazak 0 (the thesis' values are a
// measurement result, carried over), generic 2 µrad × noise_scale; an
// explicit squareness_sigma_urad is used as given.
TEST(SimCampaign, SquarenessSigmaPerProfileAndOverride) {
  for (double scale : {1.0, 0.5}) {
    GeneratorOptions o;
    o.seed = 3;
    o.spacing_mm = 100.0;
    o.noise_scale = scale;
    o.profile = "mazak";
    EXPECT_EQ(generate_machine(o).campaign.squareness_sigma_urad, 0.0) << scale;
    o.profile = "generic";
    EXPECT_EQ(generate_machine(o).campaign.squareness_sigma_urad, 2.0 * scale) << scale;
    o.squareness_sigma_urad = 3.5;
    EXPECT_EQ(generate_machine(o).campaign.squareness_sigma_urad, 3.5) << scale;
    o.profile = "mazak";
    EXPECT_EQ(generate_machine(o).campaign.squareness_sigma_urad, 3.5) << scale;
  }

  GeneratorOptions o;
  o.seed = 7;
  o.spacing_mm = 100.0;
  const GeneratedMachine exact = generate_machine(o);  // mazak, readings with noise
  const CampaignResult r = run_campaign(exact);
  EXPECT_EQ(r.squareness.ec0y, 14.569);
  EXPECT_EQ(r.squareness.eb0z, -24.362);
  EXPECT_EQ(r.squareness.ea0z, 13.757);

  o.squareness_sigma_urad = 2.0;
  const GeneratedMachine noisy = generate_machine(o);
  const CampaignResult rn = run_campaign(noisy);
  EXPECT_NE(rn.squareness.ec0y, 14.569);
  EXPECT_NE(rn.squareness.eb0z, -24.362);
  EXPECT_NE(rn.squareness.ea0z, 13.757);
  // The squareness draws come after every reading of the noise stream, and
  // the generator draws nothing for them: the machine and the laser tables
  // are the same with or without squareness noise.
  GeneratedMachine same = noisy;
  same.campaign.squareness_sigma_urad = 0.0;
  EXPECT_EQ(truth_to_yaml(same), truth_to_yaml(exact));
  EXPECT_EQ(runs_to_csv(rn), runs_to_csv(r));
  EXPECT_EQ(table_to_csv(rn), table_to_csv(r));

  for (double bad : {-0.1, std::nan(""), HUGE_VAL}) {
    o.squareness_sigma_urad = bad;
    EXPECT_THROW(generate_machine(o), std::invalid_argument) << bad;
  }
}

TEST(SimCampaign, SameSeedSameFilesOtherSeedOtherMachine) {
  const auto a = small_machine(1.0, 5), b = small_machine(1.0, 5), c = small_machine(1.0, 6);
  EXPECT_EQ(truth_to_yaml(a), truth_to_yaml(b));
  EXPECT_EQ(runs_to_csv(run_campaign(a)), runs_to_csv(run_campaign(b)));
  EXPECT_NE(table_to_csv(run_campaign(a)), table_to_csv(run_campaign(c)));
}

TEST(SimCampaign, MachineYamlFollowsTheFormat) {
  const GeneratedMachine g = small_machine(1.0);
  const YAML::Node y = YAML::Load(machine_to_yaml(g, run_campaign(g), "errors.csv"));
  EXPECT_EQ(y["chain"].as<std::string>(), "w X' b Y Z t");
  EXPECT_DOUBLE_EQ(y["travel"]["x"][0].as<double>(), -990.0);
  EXPECT_DOUBLE_EQ(y["tool_table"][1].as<double>(), 200.0);
  EXPECT_EQ(y["table"].as<std::string>(), "errors.csv");
  EXPECT_DOUBLE_EQ(y["axes"]["X"]["points"]["all"][2].as<double>(), -478.0);
  EXPECT_DOUBLE_EQ(y["axes"]["Y"]["measured_at"]["tool_length"].as<double>(), 220.0);
  EXPECT_NEAR(y["squareness"]["EB0Z"].as<double>(), -24.362, 10.0);
}

TEST(SimTruthFile, RoundTripIsExact) {
  GeneratedMachine g = small_machine(1.0);
  g.truth.effects = {parse_effect("reversal:Y:4um"), parse_effect("cyclic:X:1um:period=16")};
  const std::string text = truth_to_yaml(g);
  const GeneratedMachine back = truth_from_yaml(text, "<t>");
  EXPECT_EQ(truth_to_yaml(back), text);
  ASSERT_EQ(back.truth.effects.size(), 2u);
  for (int k = 0; k < 20; ++k) {
    TipState tip;
    tip.p = {-37.0 * k, -21.0 * k, -150.0 - 5.0 * k};
    tip.tool_length = 200.0;
    tip.dir = {k % 2 ? 1 : -1, 1, -1};
    tip.time = 100.0 * k;
    EXPECT_EQ(g.truth.deviation_um(tip), back.truth.deviation_um(tip));  // bit-exact
  }
  EXPECT_EQ(runs_to_csv(run_campaign(g)), runs_to_csv(run_campaign(back)));
}

TEST(SimTruthFile, BadFilesNameLineAndField) {
  const std::string good = truth_to_yaml(small_machine(1.0));
  auto error_of = [](const std::string& text) -> std::string {
    try {
      truth_from_yaml(text, "t.yaml");
    } catch (const InputError& e) {
      return e.what();
    }
    return "no error";
  };
  std::string bad = good;
  bad.replace(bad.find("chain: "), 21, "chain: \"w X b X Z t\"");
  EXPECT_NE(error_of(bad).find("t.yaml:"), std::string::npos) << error_of(bad);
  EXPECT_NE(error_of(bad).find("[chain]"), std::string::npos) << error_of(bad);
  bad = good;
  bad.replace(bad.find("half_range: "), 12, "half_range: -");
  EXPECT_NE(error_of(bad).find("half_range"), std::string::npos) << error_of(bad);
  bad = good;
  const std::size_t sq = bad.find("squareness_sigma_urad: ");
  ASSERT_NE(sq, std::string::npos);
  bad.replace(sq, bad.find('\n', sq) - sq, "squareness_sigma_urad: -1");
  EXPECT_NE(error_of(bad).find("[campaign.squareness_sigma_urad]: error: must be ≥ 0"),
            std::string::npos)
      << error_of(bad);
  EXPECT_NE(error_of("abbe_truth: 1\nname: x\n").find("missing key `chain`"), std::string::npos);
  EXPECT_NE(error_of("a: [\n").find("t.yaml:"), std::string::npos);
  EXPECT_NE(error_of("abbe_truth: 2\n").find("version"), std::string::npos);
}

TEST(SimMeasure, GridWalkDirectionsTimesAndEffects) {
  GeneratedMachine g = small_machine(1.0);
  GridOptions o;
  o.lo = {-300.0, -200.0, -300.0};
  o.hi = {-100.0, -100.0, -250.0};
  o.spacing_mm = 100.0;
  o.tool_length = 200.0;
  o.repeat = 2;
  const auto tips = grid_points(o);
  ASSERT_EQ(tips.size(), 2u * 3u * 2u * 2u);
  EXPECT_EQ(tips[0].dir[0], -1);  // from machine zero down to x = −300
  EXPECT_EQ(tips[1].dir[0], 1);   // then along +x
  EXPECT_DOUBLE_EQ(tips[3].time, 15.0);
  EXPECT_EQ(tips.front().set, "grid1");
  EXPECT_EQ(tips.back().set, "grid2");
  o.one_setup = true;  // both passes from one setup: one set, times going on
  const auto one = grid_points(o);
  ASSERT_EQ(one.size(), tips.size());
  for (std::size_t i = 0; i < one.size(); ++i) {
    EXPECT_EQ(one[i].set, "grid") << i;
    EXPECT_EQ(one[i].time, tips[i].time) << i;
    EXPECT_EQ(one[i].p, tips[i].p) << i;
  }
  // Noise-free measurement equals the truth; an injected reversal changes only y.
  const auto clean = measure(g.truth, tips, 0.0, 1);
  g.truth.effects.push_back(parse_effect("reversal:Y:4um"));
  const auto with = measure(g.truth, tips, 0.0, 1);
  for (std::size_t i = 0; i < tips.size(); ++i) {
    const Eigen::Vector3d d = with[i].deviation_um - clean[i].deviation_um;
    EXPECT_NEAR(d.y(), 2.0 * tips[i].dir[1], 1e-12);
    EXPECT_EQ(d.x(), 0.0);
  }
  const std::string csv = measured_to_csv(clean);
  EXPECT_EQ(csv.substr(0, csv.find('\n')), "x,y,z,dx,dy,dz,t,vx,vy,vz,nx,ny,nz,dn,tool_length,set");
}

}  // namespace
}  // namespace abbe::sim
