#include "abbe/report/predicted_path.hpp"

#include <algorithm>
#include <sstream>

#include "abbe/pipeline/interpreter_setup.hpp"
#include "abbe/pipeline/model_set.hpp"
#include "abbe/pipeline/program_path.hpp"

namespace abbe::report {
namespace {

// Drops every other kept point (stride doubles).
void thin(PredictedPath& r) {
  auto keep_even = [](auto& v) {
    std::size_t j = 0;
    for (std::size_t i = 0; i < v.size(); i += 2) v[j++] = v[i];
    v.resize(j);
  };
  keep_even(r.nominal);
  keep_even(r.line);
  keep_even(r.path_length);
  for (auto& d : r.deviation_um) keep_even(d);
  r.stride *= 2;
}

}  // namespace

PredictedPath predict_program(const machine::Machine& machine, std::istream& in,
                              const std::string& file, const PredictPathOptions& o) {
  PredictedPath r;
  r.program = file;
  r.machine = machine.name();
  r.models = o.models;
  // The whole text is kept: the report shows source lines on hover.
  std::string text{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  std::istringstream program(text);

  pipeline::ModelSet models(machine, o.models);
  r.deviation_um.resize(models.size());
  pipeline::PathOptions po;
  po.fragment.step = o.step;
  po.fragment.rapid_rate = o.rapid_rate;
  po.min_reversal_mm = o.min_reversal_mm;
  po.dialect = o.dialect;

  double length = 0.0;
  Eigen::Vector3d previous = Eigen::Vector3d::Zero();
  const std::size_t max_points = std::max<std::size_t>(o.max_points, 16);
  pipeline::run_path(program, file, pipeline::interpreter_config(machine), po,
                     [&](const path::PathPoint& pp) {
                       models.evaluate(pipeline::eval_point(pp), file, pp.line);
                       if (r.total_points > 0) length += (pp.p - previous).norm();
                       previous = pp.p;
                       if (r.total_points % r.stride == 0) {
                         r.nominal.push_back(pp.p);
                         r.line.push_back(pp.line);
                         r.path_length.push_back(length);
                         for (std::size_t i = 0; i < models.size(); ++i)
                           r.deviation_um[i].push_back(models.deviations()[i].e_um);
                         if (r.nominal.size() >= max_points) thin(r);
                       }
                       ++r.total_points;
                       if (o.progress && (r.total_points & 1023) == 0) {
                         const auto pos = program.tellg();
                         if (pos >= 0) o.progress(static_cast<std::uint64_t>(pos));
                       }
                     });
  if (o.progress) o.progress(text.size());

  for (std::size_t i = 0; i < models.size(); ++i) {
    const pipeline::ModelStats& s = models.stats()[i];
    ModelPathStats& out = r.stats.emplace_back();
    out.model = o.models[i];
    out.max_abs_um = s.max_abs_um;
    out.rms_um = s.rms_um();
    out.max_um = s.max_um;
    out.max_line = s.max_line;
    out.out_of_range_lookups = models.out_of_range_lookups(i);
  }

  // Source text of the lines the kept points come from.
  for (std::size_t l : r.line) r.source.emplace(l, std::string());
  std::size_t n = 0, start = 0;
  auto it = r.source.begin();
  for (std::size_t i = 0; i <= text.size() && it != r.source.end(); ++i) {
    if (i < text.size() && text[i] != '\n') continue;
    ++n;
    if (n == it->first) {
      std::string s = text.substr(start, i - start);
      if (!s.empty() && s.back() == '\r') s.pop_back();
      if (s.size() > 80) s = s.substr(0, 77) + "...";
      it->second = s;
      ++it;
    }
    start = i + 1;
  }
  return r;
}

}  // namespace abbe::report
