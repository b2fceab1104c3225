#include "abbe/diagnose/residuals.hpp"

#include <algorithm>
#include <cmath>

#include "abbe/diagnose/context.hpp"
#include "abbe/diagnose/overlay.hpp"
#include "abbe/io/input_error.hpp"
#include "abbe/model/error_model.hpp"

namespace abbe::diagnose {

ResidualStats residual_stats(const Problem& problem, const Eigen::VectorXd& r) {
  ResidualStats s;
  std::vector<double> d2(problem.points.size(), 0.0);
  for (std::size_t o = 0; o < problem.obs.size(); ++o)
    d2[problem.obs[o].point] += r[static_cast<Eigen::Index>(o)] * r[static_cast<Eigen::Index>(o)];
  double sum = 0.0;
  for (double v : d2) {
    sum += v;
    s.max_um = std::max(s.max_um, std::sqrt(v));
  }
  s.rms_um = d2.empty() ? 0.0 : std::sqrt(sum / static_cast<double>(d2.size()));
  return s;
}

Problem build_problem(const machine::Machine& machine, const io::MeasuredData& data,
                      model::ModelKind base, const Overlay* extend) {
  Problem pb;
  ContextBuilder builder(machine, base);
  pb.base_model = model::to_string(base);
  pb.other_model = model::to_string(builder.other());
  const std::vector<model::ModelKind> kinds = model::parse_model_list("all");
  const std::size_t n_models = kinds.size();
  std::vector<model::ErrorModel> models;
  std::vector<model::ModelData> mdata(n_models);
  for (auto k : kinds) models.emplace_back(machine, k);
  std::vector<double> ys;
  std::vector<std::vector<double>> model_ys(n_models);

  pb.points.reserve(data.rows.size());
  for (const io::MeasuredRow& row : data.rows) {
    model::EvalPoint ep;
    ep.p = row.p;
    ep.tool_length = row.tool_length_or(machine.tool_length());
    ep.dir = row.v;
    ep.time = row.t;
    Eigen::Vector3d pred;
    PointContext pc;
    std::vector<Eigen::Vector3d> mp(n_models);
    try {
      pc = builder.make(ep, row.set, pred);
      for (std::size_t m = 0; m < n_models; ++m) mp[m] = models[m].evaluate(ep, mdata[m]).e_um;
    } catch (const InputError& e) {
      throw InputError({data.file, row.line, 0, e.where().field, ""}, e.message());
    }
    if (extend) pred += extend->evaluate(pc);
    const auto ip = static_cast<std::uint32_t>(pb.points.size());
    Eigen::Vector3d measured = Eigen::Vector3d::Zero();
    std::array<bool, 3> has{false, false, false};
    for (int k = 0; k < 3; ++k)
      if (row.has(k)) {
        has[static_cast<std::size_t>(k)] = true;
        measured[k] = row.d[static_cast<std::size_t>(k)];
      }
    auto add = [&](const Eigen::Vector3d& u, double meas) {
      pb.obs.push_back({ip, u});
      ys.push_back(meas - u.dot(pred));
      for (std::size_t m = 0; m < n_models; ++m) model_ys[m].push_back(meas - u.dot(mp[m]));
    };
    if (has[0] || has[1] || has[2]) {
      for (int k = 0; k < 3; ++k)
        if (has[static_cast<std::size_t>(k)]) {
          add(Eigen::Vector3d::Unit(k), measured[k]);
          pb.direction_present[static_cast<std::size_t>(k)] = true;
        }
    } else {
      add(row.n, row.dn);  // surface point: only the deviation along the normal
      for (int k = 0; k < 3; ++k)
        if (std::abs(row.n[k]) > 1e-9) pb.direction_present[static_cast<std::size_t>(k)] = true;
    }
    if (std::find(pb.sets.begin(), pb.sets.end(), row.set) == pb.sets.end())
      pb.sets.push_back(row.set);
    pb.points.push_back(std::move(pc));
    pb.lines.push_back(row.line);
  }
  pb.y = Eigen::Map<Eigen::VectorXd>(ys.data(), static_cast<Eigen::Index>(ys.size()));
  for (std::size_t m = 0; m < n_models; ++m) {
    Eigen::VectorXd r = Eigen::Map<Eigen::VectorXd>(model_ys[m].data(),
                                                    static_cast<Eigen::Index>(model_ys[m].size()));
    ResidualStats s = residual_stats(pb, r);
    s.model = model::to_string(kinds[m]);
    pb.models.push_back(s);
  }
  for (std::size_t v = 0; v < 4; ++v) {
    pb.var_lo[v] = 1e300;
    pb.var_hi[v] = -1e300;
  }
  for (const PointContext& pc : pb.points)
    for (std::size_t v = 0; v < 4; ++v) {
      const double x = v < 3 ? pc.s[static_cast<Eigen::Index>(v)] : pc.t;
      pb.var_lo[v] = std::min(pb.var_lo[v], x);
      pb.var_hi[v] = std::max(pb.var_hi[v], x);
    }
  for (machine::Axis a : machine::kAxes) {
    const auto& tr = machine.travel(a);
    const int i = machine::index(a);
    pb.travel_mid[i] = 0.5 * (tr.min + tr.max);
    pb.travel_half[i] = tr.max > tr.min ? 0.5 * (tr.max - tr.min) : 1.0;
  }
  return pb;
}

}  // namespace abbe::diagnose
