#include "abbe/report/predicted_path.hpp"

#include "abbe/machine/interpreter_setup.hpp"

#include <fmt/format.h>

#include <array>
#include <cmath>
#include <sstream>

#include "abbe/gcode/program.hpp"
#include "abbe/io/input_error.hpp"
#include "abbe/model/error_model.hpp"
#include "abbe/path/fragmenter.hpp"

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

  std::vector<model::ErrorModel> models;
  for (auto k : o.models) models.emplace_back(machine, k);
  std::vector<model::ModelData> data(models.size());
  std::vector<double> sum_d2(models.size(), 0.0);
  r.stats.resize(models.size());
  r.deviation_um.resize(models.size());
  for (std::size_t i = 0; i < models.size(); ++i) r.stats[i].model = o.models[i];

  const gcode::InterpreterConfig config = machine::interpreter_config(machine);
  path::FragmentOptions fo;
  fo.step = o.step;
  fo.rapid_rate = o.rapid_rate;
  path::Fragmenter fragmenter(fo);

  double length = 0.0;
  Eigen::Vector3d previous = Eigen::Vector3d::Zero();
  std::vector<Eigen::Vector3d> e(models.size());
  const std::size_t max_points = std::max<std::size_t>(o.max_points, 16);
  std::array<bool, 3> hold{false, false, false};
  std::array<std::int8_t, 3> dir{0, 0, 0};
  const path::PointSink sink = [&](const path::PathPoint& pp) {
    model::EvalPoint p;
    p.p = pp.p;
    p.tool_length = pp.tool_length;
    for (std::size_t a = 0; a < 3; ++a)
      if (!hold[a]) dir[a] = pp.dir[a];
    p.dir = dir;
    p.time = pp.time;
    for (std::size_t i = 0; i < models.size(); ++i) {
      try {
        e[i] = models[i].evaluate(p, data[i]).e_um;
      } catch (const InputError& err) {
        throw InputError({file, pp.line, 0, err.where().field, ""},
                         fmt::format("at the point ({:.4f}, {:.4f}, {:.4f}) mm: {}", p.p.x(),
                                     p.p.y(), p.p.z(), err.message()));
      }
      const double d = e[i].norm();
      ModelPathStats& s = r.stats[i];
      s.max_abs_um = s.max_abs_um.cwiseMax(e[i].cwiseAbs());
      sum_d2[i] += d * d;
      if (d > s.max_um || r.total_points == 0) s.max_um = d, s.max_line = pp.line;
    }
    if (r.total_points > 0) length += (pp.p - previous).norm();
    previous = pp.p;
    if (r.total_points % r.stride == 0) {
      r.nominal.push_back(pp.p);
      r.line.push_back(pp.line);
      r.path_length.push_back(length);
      for (std::size_t i = 0; i < models.size(); ++i) r.deviation_um[i].push_back(e[i]);
      if (r.nominal.size() >= max_points) thin(r);
    }
    ++r.total_points;
    if (o.progress && (r.total_points & 1023) == 0) {
      const auto pos = program.tellg();
      if (pos >= 0) o.progress(static_cast<std::uint64_t>(pos));
    }
  };
  gcode::run_program(program, file, config, [&](const gcode::Motion& m) {
    for (Eigen::Index a = 0; a < 3; ++a)
      hold[static_cast<std::size_t>(a)] = o.min_reversal_mm > 0.0 &&
                                          m.kind != gcode::MotionKind::arc &&
                                          std::abs(m.end[a] - m.start[a]) < o.min_reversal_mm;
    fragmenter.add(m, sink);
  });
  if (o.progress) o.progress(text.size());

  for (std::size_t i = 0; i < models.size(); ++i) {
    r.stats[i].rms_um =
        r.total_points ? std::sqrt(sum_d2[i] / static_cast<double>(r.total_points)) : 0.0;
    r.stats[i].out_of_range_lookups = data[i].out_of_range_lookups;
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
