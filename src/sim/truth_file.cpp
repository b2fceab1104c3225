#include "abbe/sim/truth_file.hpp"

#include <yaml-cpp/yaml.h>

#include <cmath>
#include <stdexcept>

#include "abbe/io/input_error.hpp"
#include "abbe/sim/text_file.hpp"
#include "src/io/yaml_reader.hpp"

namespace abbe::sim {

namespace {

constexpr int kFormatVersion = 1;

void emit_vector(YAML::Emitter& y, const Eigen::Vector3d& v) {
  y << YAML::Flow << YAML::BeginSeq << v.x() << v.y() << v.z() << YAML::EndSeq;
}

}  // namespace

std::string truth_to_yaml(const GeneratedMachine& machine) {
  const TruthMachine& t = machine.truth;
  const CampaignSetup& c = machine.campaign;
  YAML::Emitter y;
  y.SetDoublePrecision(17);
  y << YAML::Comment(
      "Ground truth of a SYNTHETIC virtual machine (abbe simulate). Rebuilds the machine exactly.");
  y << YAML::BeginMap;
  y << YAML::Key << "abbe_truth" << YAML::Value << kFormatVersion;
  y << YAML::Key << "name" << YAML::Value << t.name;
  y << YAML::Key << "chain" << YAML::Value << YAML::DoubleQuoted << t.chain.text();
  y << YAML::Key << "tool_length" << YAML::Value << t.tool_length;
  y << YAML::Key << "tool_table" << YAML::Value << YAML::BeginMap;
  for (const auto& [h, len] : t.tool_table) y << YAML::Key << h << YAML::Value << len;
  y << YAML::EndMap;
  y << YAML::Key << "squareness" << YAML::Value << YAML::BeginMap;
  y << YAML::Key << "EC0Y" << YAML::Value << t.squareness.ec0y;
  y << YAML::Key << "EB0Z" << YAML::Value << t.squareness.eb0z;
  y << YAML::Key << "EA0Z" << YAML::Value << t.squareness.ea0z;
  y << YAML::EndMap;
  y << YAML::Key << "axes" << YAML::Value << YAML::BeginMap;
  for (int j = 0; j < 3; ++j) {
    const AxisTruth& a = t.axes[static_cast<std::size_t>(j)];
    y << YAML::Key << std::string(1, axis_letter(j)) << YAML::Value << YAML::BeginMap;
    y << YAML::Key << "travel" << YAML::Value << YAML::Flow << YAML::BeginSeq << a.travel_min
      << a.travel_max << YAML::EndSeq;
    y << YAML::Key << "pivot" << YAML::Value;
    emit_vector(y, a.pivot0);
    y << YAML::Key << "components" << YAML::Value << YAML::BeginMap;
    for (int k = 0; k < 6; ++k) {
      const ErrorComponent& e = a.components[static_cast<std::size_t>(k)];
      y << YAML::Key << component_name(j, k) << YAML::Value << YAML::BeginMap;
      y << YAML::Key << "centre" << YAML::Value << e.centre;
      y << YAML::Key << "half_range" << YAML::Value << e.half_range;
      y << YAML::Key << "poly" << YAML::Value << YAML::Flow << e.poly;
      y << YAML::Key << "waves" << YAML::Value << YAML::BeginSeq;
      for (const Wave& w : e.waves)
        y << YAML::Flow << YAML::BeginSeq << w.amplitude << w.wavelength << w.phase << YAML::EndSeq;
      y << YAML::EndSeq;
      y << YAML::Key << "reversal" << YAML::Value << e.reversal;
      y << YAML::Key << "reversal_slope" << YAML::Value << e.reversal_slope;
      y << YAML::EndMap;
    }
    y << YAML::EndMap << YAML::EndMap;
  }
  y << YAML::EndMap;
  y << YAML::Key << "effects" << YAML::Value << YAML::BeginSeq;
  for (const Effect& e : t.effects) y << e.text;
  y << YAML::EndSeq;
  y << YAML::Key << "campaign" << YAML::Value << YAML::BeginMap;
  y << YAML::Key << "spacing_mm" << YAML::Value << c.spacing_mm;
  y << YAML::Key << "runs" << YAML::Value << c.runs;
  y << YAML::Key << "seed" << YAML::Value << c.seed;
  y << YAML::Key << "squareness_sigma_urad" << YAML::Value << c.squareness_sigma_urad;
  y << YAML::Key << "axes" << YAML::Value << YAML::BeginMap;
  for (int j = 0; j < 3; ++j) {
    const AxisRecord& r = c.axes[static_cast<std::size_t>(j)];
    y << YAML::Key << std::string(1, axis_letter(j)) << YAML::Value << YAML::BeginMap;
    y << YAML::Key << "measured_at" << YAML::Value;
    emit_vector(y, r.measured_at);
    y << YAML::Key << "tool_length" << YAML::Value << r.tool_length;
    y << YAML::Key << "point" << YAML::Value;
    emit_vector(y, r.point);
    y << YAML::Key << "sigma" << YAML::Value << YAML::Flow << YAML::BeginMap;
    for (int k = 0; k < 6; ++k)
      y << YAML::Key << component_name(j, k) << YAML::Value << r.sigma[static_cast<std::size_t>(k)];
    y << YAML::EndMap << YAML::EndMap;
  }
  y << YAML::EndMap << YAML::EndMap;
  y << YAML::EndMap;
  return std::string(y.c_str()) + "\n";
}

GeneratedMachine truth_from_yaml(const std::string& text, const std::string& file) {
  const io::YamlReader r(file, text);
  const YAML::Node root = r.load(text);
  if (!root.IsMap()) r.fail(root, "", "a truth file is a YAML mapping");
  const auto version = r.integer(r.required(root, "abbe_truth", ""), "abbe_truth");
  if (version != kFormatVersion)
    r.fail(root["abbe_truth"], "abbe_truth", "unsupported truth file version");
  GeneratedMachine g;
  TruthMachine& t = g.truth;
  t.name = r.string(r.required(root, "name", ""), "name");
  const YAML::Node chain = r.required(root, "chain", "");
  try {
    t.chain = ChainLayout::parse(r.string(chain, "chain"));
  } catch (const std::invalid_argument& e) {
    r.fail(chain, "chain", e.what());
  }
  t.tool_length = r.number(r.required(root, "tool_length", ""), "tool_length");
  if (const YAML::Node tt = root["tool_table"]; tt.IsDefined() && !tt.IsNull()) {
    if (!tt.IsMap()) r.fail(tt, "tool_table", "expected H: length");
    for (const auto& kv : tt)
      t.tool_table[static_cast<int>(r.integer(kv.first, "tool_table"))] =
          r.number(kv.second, "tool_table");
  }
  const YAML::Node sq = r.required(root, "squareness", "");
  t.squareness.ec0y = r.number(r.required(sq, "EC0Y", "squareness"), "squareness.EC0Y");
  t.squareness.eb0z = r.number(r.required(sq, "EB0Z", "squareness"), "squareness.EB0Z");
  t.squareness.ea0z = r.number(r.required(sq, "EA0Z", "squareness"), "squareness.EA0Z");
  const YAML::Node axes = r.required(root, "axes", "");
  for (int j = 0; j < 3; ++j) {
    const std::string an(1, axis_letter(j));
    const YAML::Node a = r.required(axes, an, "axes");
    const std::string path = "axes." + an;
    AxisTruth& ax = t.axes[static_cast<std::size_t>(j)];
    const auto travel = r.numbers(r.required(a, "travel", path), path + ".travel");
    if (travel.size() != 2 || !(travel[0] < travel[1]))
      r.fail(a["travel"], path + ".travel", "expected [min, max] with min < max");
    ax.travel_min = travel[0];
    ax.travel_max = travel[1];
    ax.pivot0 = r.vec3(r.required(a, "pivot", path), path + ".pivot");
    const YAML::Node comps = r.required(a, "components", path);
    for (int k = 0; k < 6; ++k) {
      const std::string cn = component_name(j, k);
      const std::string cp = path + ".components." + cn;
      const YAML::Node cnode = comps[cn];
      if (!cnode.IsDefined()) continue;  // missing component: zero
      ErrorComponent& e = ax.components[static_cast<std::size_t>(k)];
      e.centre = r.number(r.required(cnode, "centre", cp), cp + ".centre");
      e.half_range = r.number(r.required(cnode, "half_range", cp), cp + ".half_range");
      if (!(e.half_range > 0.0)) r.fail(cnode["half_range"], cp + ".half_range", "must be > 0");
      e.poly = r.numbers(r.required(cnode, "poly", cp), cp + ".poly");
      const YAML::Node waves = r.required(cnode, "waves", cp);
      if (!waves.IsSequence()) r.fail(waves, cp + ".waves", "expected a list of [a, λ, φ]");
      for (std::size_t w = 0; w < waves.size(); ++w) {
        const auto v = r.numbers(waves[w], cp + ".waves");
        if (v.size() != 3 || !(v[1] > 0.0))
          r.fail(waves[w], cp + ".waves", "expected [amplitude, wavelength > 0, phase]");
        e.waves.push_back({v[0], v[1], v[2]});
      }
      e.reversal = r.number(r.required(cnode, "reversal", cp), cp + ".reversal");
      e.reversal_slope = r.number(r.required(cnode, "reversal_slope", cp), cp + ".reversal_slope");
    }
  }
  if (const YAML::Node effects = root["effects"]; effects.IsDefined() && !effects.IsNull()) {
    if (!effects.IsSequence()) r.fail(effects, "effects", "expected a list of effect strings");
    for (std::size_t i = 0; i < effects.size(); ++i) {
      try {
        t.effects.push_back(parse_effect(r.string(effects[i], "effects")));
      } catch (const std::invalid_argument& e) {
        r.fail(effects[i], "effects", e.what());
      }
    }
  }
  const YAML::Node c = r.required(root, "campaign", "");
  CampaignSetup& cs = g.campaign;
  cs.spacing_mm = r.number(r.required(c, "spacing_mm", "campaign"), "campaign.spacing_mm");
  if (!(cs.spacing_mm > 0.0)) r.fail(c["spacing_mm"], "campaign.spacing_mm", "must be > 0");
  cs.runs = static_cast<int>(r.integer(r.required(c, "runs", "campaign"), "campaign.runs"));
  if (cs.runs < 2) r.fail(c["runs"], "campaign.runs", "must be ≥ 2");
  const YAML::Node seed = r.required(c, "seed", "campaign");
  try {
    cs.seed = seed.as<std::uint64_t>();
  } catch (const YAML::Exception&) {
    r.fail(seed, "campaign.seed", "expected a non-negative integer");
  }
  cs.squareness_sigma_urad = r.number(r.required(c, "squareness_sigma_urad", "campaign"),
                                      "campaign.squareness_sigma_urad");
  if (cs.squareness_sigma_urad < 0.0)
    r.fail(c["squareness_sigma_urad"], "campaign.squareness_sigma_urad", "must be ≥ 0");
  const YAML::Node caxes = r.required(c, "axes", "campaign");
  for (int j = 0; j < 3; ++j) {
    const std::string an(1, axis_letter(j));
    const std::string path = "campaign.axes." + an;
    const YAML::Node a = r.required(caxes, an, "campaign.axes");
    AxisRecord& rec = cs.axes[static_cast<std::size_t>(j)];
    rec.measured_at = r.vec3(r.required(a, "measured_at", path), path + ".measured_at");
    rec.tool_length = r.number(r.required(a, "tool_length", path), path + ".tool_length");
    rec.point = r.vec3(r.required(a, "point", path), path + ".point");
    const YAML::Node sig = r.required(a, "sigma", path);
    for (int k = 0; k < 6; ++k) {
      const std::string cn = component_name(j, k);
      const double v = r.number(r.required(sig, cn, path + ".sigma"), path + ".sigma." + cn);
      if (v < 0.0) r.fail(sig[cn], path + ".sigma." + cn, "must be ≥ 0");
      rec.sigma[static_cast<std::size_t>(k)] = v;
    }
  }
  return g;
}

GeneratedMachine load_truth_file(const std::string& path) {
  return truth_from_yaml(read_text_file(path), path);
}

}  // namespace abbe::sim
