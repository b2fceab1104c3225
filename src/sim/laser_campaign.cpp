#include "abbe/sim/laser_campaign.hpp"

#include <fmt/format.h>
#include <yaml-cpp/yaml.h>

#include <cmath>

#include "abbe/sim/random.hpp"

namespace abbe::sim {

std::vector<double> campaign_targets(const AxisTruth& axis, double spacing_mm) {
  std::vector<double> targets;
  const double length = axis.travel_max - axis.travel_min;
  const auto n = static_cast<long>(std::floor(length / spacing_mm + 1e-9));
  for (long k = 0; k <= n; ++k)
    targets.push_back(axis.travel_min + static_cast<double>(k) * spacing_mm);
  if (axis.travel_max - targets.back() > 1e-6) targets.push_back(axis.travel_max);
  return targets;
}

CampaignResult run_campaign(const GeneratedMachine& machine) {
  const TruthMachine& truth = machine.truth;
  const CampaignSetup& setup = machine.campaign;
  Random rng(setup.seed);
  CampaignResult out;
  for (int j = 0; j < 3; ++j) {
    const AxisRecord& rec = setup.axes[static_cast<std::size_t>(j)];
    const Eigen::Vector3d s_meas = TruthMachine::axis_positions(rec.measured_at, rec.tool_length);
    const auto targets =
        campaign_targets(truth.axes[static_cast<std::size_t>(j)], setup.spacing_mm);
    const std::size_t n = targets.size();
    // Sums per component, target and direction for the table means.
    std::vector<std::array<double, 6>> sum_up(n), sum_down(n);
    for (int run = 1; run <= setup.runs; ++run) {
      for (int dir : {+1, -1}) {
        for (std::size_t kk = 0; kk < n; ++kk) {
          const std::size_t k = dir > 0 ? kk : n - 1 - kk;  // up the axis, then down
          Eigen::Vector3d s = s_meas;
          s[j] = targets[k];
          // The reflector point moves with the axes of U(j) (only j moves here).
          Eigen::Vector3d m = rec.point;
          for (int i = 0; i < 3; ++i)
            if (truth.chain.moves(j, i)) m[i] += s[i] - s_meas[i];
          const Eigen::Vector3d lin = truth.laser_linear_reading_um(j, s, dir, m);
          const Eigen::Vector3d ang = truth.rotation_urad(j, targets[k], dir);
          for (int c = 0; c < 6; ++c) {
            const double sigma = rec.sigma[static_cast<std::size_t>(c)];
            double v = c < 3 ? lin[c] : ang[c - 3];
            if (sigma > 0.0) v += sigma * rng.normal();
            out.runs.push_back({j, c, targets[k], run, dir, v});
            (dir > 0 ? sum_up : sum_down)[k][static_cast<std::size_t>(c)] += v;
          }
        }
      }
    }
    for (int c = 0; c < 6; ++c)
      for (std::size_t k = 0; k < n; ++k)
        out.table.push_back({j, c, targets[k], sum_up[k][static_cast<std::size_t>(c)] / setup.runs,
                             sum_down[k][static_cast<std::size_t>(c)] / setup.runs});
  }
  // Squareness, measured separately.
  const double sq = setup.squareness_sigma_urad;
  out.squareness = truth.squareness;
  if (sq > 0.0) {
    out.squareness.ec0y += sq * rng.normal();
    out.squareness.eb0z += sq * rng.normal();
    out.squareness.ea0z += sq * rng.normal();
  }
  return out;
}

std::string runs_to_csv(const CampaignResult& result) {
  std::string out = "axis,component,target_mm,run,direction,deviation\n";
  for (const RunReading& r : result.runs)
    out +=
        fmt::format("{},{},{},{},{},{:.4f}\n", "XYZ"[r.axis], component_name(r.axis, r.component),
                    r.target_mm, r.run, r.dir > 0 ? "up" : "down", r.deviation);
  return out;
}

std::string table_to_csv(const CampaignResult& result) {
  std::string out = "axis,component,position_mm,direction,value\n";
  for (const TableEntry& e : result.table) {
    const std::string name = component_name(e.axis, e.component);
    out += fmt::format("{},{},{},fwd,{:.4f}\n", "XYZ"[e.axis], name, e.position_mm, e.fwd);
    out += fmt::format("{},{},{},rev,{:.4f}\n", "XYZ"[e.axis], name, e.position_mm, e.rev);
  }
  return out;
}

namespace {
YAML::Emitter& flow_vector(YAML::Emitter& y, const Eigen::Vector3d& v) {
  y << YAML::Flow << YAML::BeginSeq << v.x() << v.y() << v.z() << YAML::EndSeq;
  return y;
}
}  // namespace

std::string machine_to_yaml(const GeneratedMachine& machine, const CampaignResult& result,
                            const std::string& table_file) {
  const TruthMachine& t = machine.truth;
  YAML::Emitter y;
  y.SetDoublePrecision(10);
  y << YAML::BeginMap;
  y << YAML::Key << "name" << YAML::Value << t.name;
  y << YAML::Key << "chain" << YAML::Value << YAML::DoubleQuoted << t.chain.text();
  y << YAML::Key << "travel" << YAML::Value << YAML::BeginMap;
  for (int j = 0; j < 3; ++j) {
    const AxisTruth& a = t.axes[static_cast<std::size_t>(j)];
    y << YAML::Key << std::string(1, "xyz"[j]) << YAML::Value << YAML::Flow << YAML::BeginSeq
      << a.travel_min << a.travel_max << YAML::EndSeq;
  }
  y << YAML::EndMap;
  y << YAML::Key << "tool_length" << YAML::Value << t.tool_length;
  if (!t.tool_table.empty()) {
    y << YAML::Key << "tool_table" << YAML::Value << YAML::BeginMap;
    for (const auto& [h, len] : t.tool_table) y << YAML::Key << h << YAML::Value << len;
    y << YAML::EndMap;
  }
  y << YAML::Key << "squareness" << YAML::Value << YAML::BeginMap;
  y << YAML::Key << "EC0Y" << YAML::Value << std::round(result.squareness.ec0y * 1000.0) / 1000.0;
  y << YAML::Key << "EB0Z" << YAML::Value << std::round(result.squareness.eb0z * 1000.0) / 1000.0;
  y << YAML::Key << "EA0Z" << YAML::Value << std::round(result.squareness.ea0z * 1000.0) / 1000.0;
  y << YAML::EndMap;
  y << YAML::Key << "table" << YAML::Value << table_file;
  y << YAML::Key << "out_of_range" << YAML::Value << "clamp";
  y << YAML::Key << "axes" << YAML::Value << YAML::BeginMap;
  for (int j = 0; j < 3; ++j) {
    const AxisRecord& r = machine.campaign.axes[static_cast<std::size_t>(j)];
    y << YAML::Key << std::string(1, "XYZ"[j]) << YAML::Value << YAML::BeginMap;
    y << YAML::Key << "measured_at" << YAML::Value << YAML::Flow << YAML::BeginMap;
    y << YAML::Key << "x" << YAML::Value << r.measured_at.x();
    y << YAML::Key << "y" << YAML::Value << r.measured_at.y();
    y << YAML::Key << "z" << YAML::Value << r.measured_at.z();
    y << YAML::Key << "tool_length" << YAML::Value << r.tool_length;
    y << YAML::EndMap;
    y << YAML::Key << "points" << YAML::Value << YAML::BeginMap;
    y << YAML::Key << "all" << YAML::Value;
    flow_vector(y, r.point);
    y << YAML::EndMap;
    y << YAML::EndMap;
  }
  y << YAML::EndMap;
  y << YAML::EndMap;
  return std::string(y.c_str()) + "\n";
}

}  // namespace abbe::sim
