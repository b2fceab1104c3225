#include "abbe/pipeline/aligned_prediction.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <nlohmann/json.hpp>
#include <stdexcept>

#include "abbe/io/input_error.hpp"
#include "abbe/io/units.hpp"
#include "abbe/pipeline/interpreter_setup.hpp"
#include "abbe/pipeline/point_reader.hpp"
#include "abbe/pipeline/program_path.hpp"

namespace abbe::pipeline {
namespace {

struct StoredPoint {
  model::EvalPoint point;
  std::size_t line = 0;
  bool cutting = true;  // on a feed motion (every point of a CSV of points)
};

nlohmann::json stats_json(const ModelStats& s) {
  return {{"max_abs_dx_um", s.max_abs_um.x()},
          {"max_abs_dy_um", s.max_abs_um.y()},
          {"max_abs_dz_um", s.max_abs_um.z()},
          {"rms_d_um", s.rms_um()},
          {"max_d_um", s.max_um}};
}

nlohmann::json vec_json(const Eigen::Vector3d& v) {
  return {{"x", v.x()}, {"y", v.y()}, {"z", v.z()}};
}

}  // namespace

const char* to_string(AlignMethod method) {
  switch (method) {
    case AlignMethod::best_fit:
      return "best-fit";
    case AlignMethod::datums:
      return "datums";
    case AlignMethod::none:
      break;
  }
  return "none";
}

AlignMethod parse_align_method(const std::string& name) {
  if (name == "none") return AlignMethod::none;
  if (name == "best-fit") return AlignMethod::best_fit;
  if (name == "datums") return AlignMethod::datums;
  throw std::invalid_argument("unknown alignment '" + name + "' (none, best-fit, datums)");
}

LineSet LineSet::parse(const std::string& text, const std::string& field) {
  LineSet set;
  std::size_t pos = 0;
  auto fail = [&](const std::string& what) {
    SourceLocation where;
    where.file = "<command line>";
    where.column = pos + 1;
    where.field = field;
    where.source_line = text;
    throw InputError(where, what + " (source lines such as 12-30,45)");
  };
  auto number = [&]() {
    if (pos >= text.size() || !std::isdigit(static_cast<unsigned char>(text[pos])))
      fail("expected a line number");
    std::size_t v = 0;
    while (pos < text.size() && std::isdigit(static_cast<unsigned char>(text[pos]))) {
      if (v > 100000000000ULL) fail("line number too large");
      v = v * 10 + static_cast<std::size_t>(text[pos] - '0');
      ++pos;
    }
    return v;
  };
  if (text.empty()) fail("empty set of lines");
  while (true) {
    const std::size_t first = number();
    std::size_t last = first;
    if (pos < text.size() && text[pos] == '-') {
      ++pos;
      const std::size_t at = pos;
      last = number();
      if (last < first) {
        pos = at;
        fail("a range must not run backwards");
      }
    }
    set.ranges_.emplace_back(first, last);
    if (pos == text.size()) break;
    if (text[pos] != ',') fail("unexpected character");
    ++pos;
  }
  return set;
}

bool LineSet::contains(std::size_t line) const {
  for (const auto& r : ranges_)
    if (line >= r.first && line <= r.second) return true;
  return false;
}

AlignedPrediction predict_aligned(std::istream& in, const std::string& file,
                                  const machine::Machine& machine, const PredictOptions& options,
                                  const AlignOptions& align, const PredictionSink& progress,
                                  const AlignedSink& sink) {
  std::vector<StoredPoint> stored;
  std::vector<std::vector<model::Deviation>> devs(options.models.size());
  std::vector<std::vector<double>> norms(options.models.size());
  ModelSet models(machine, options.models, options.extension);
  // The walk of `predict`, keeping whether a point lies on a feed motion.
  auto evaluate = [&](const model::EvalPoint& p, std::size_t line, bool cutting) {
    models.evaluate(p, file, line, !cutting);
    stored.push_back({p, line, cutting});
    for (std::size_t m = 0; m < models.size(); ++m) {
      devs[m].push_back(models.deviations()[m]);
      norms[m].push_back(models.norms_um()[m]);
    }
    if (progress) progress(p, line, models);
  };
  if (options.input == PredictInput::points) {
    PointReader reader(in, file, machine.tool_length());
    model::EvalPoint p;
    std::size_t line = 0;
    while (reader.next(p, line)) evaluate(p, line, true);
  } else {
    run_path(in, file, interpreter_config(machine), options.path, [&](const path::PathPoint& pp) {
      evaluate(eval_point(pp), pp.line,
               pp.kind == gcode::MotionKind::linear || pp.kind == gcode::MotionKind::arc);
    });
  }
  AlignedPrediction out;
  out.summary = summarize(models, machine, file);
  out.summary.moves = options.input == PredictInput::program;

  // The part: the cutting points; the datum sets among them.
  std::vector<std::size_t> part;
  DatumIndices datums;
  for (std::size_t i = 0; i < stored.size(); ++i) {
    if (!stored[i].cutting) continue;
    const std::size_t k = part.size();
    part.push_back(i);
    if (align.method != AlignMethod::datums) continue;
    const std::size_t line = stored[i].line;
    if (align.primary.contains(line)) datums.primary.push_back(k);
    if (align.secondary.contains(line)) datums.secondary.push_back(k);
    if (align.tertiary.contains(line)) datums.tertiary.push_back(k);
  }
  PartAlignmentSummary& a = out.alignment;
  a.method = align.method;
  a.part_points = part.size();
  a.datum_points[0] = datums.primary.size();
  a.datum_points[1] = datums.secondary.size();
  a.datum_points[2] = datums.tertiary.size();

  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
  for (std::size_t i : part) centroid += stored[i].point.p;
  if (!part.empty()) centroid /= static_cast<double>(part.size());

  for (std::size_t m = 0; m < options.models.size(); ++m) {
    PartPoints pts;
    for (std::size_t i : part) pts.add(stored[i].point.p, devs[m][i].e_um);
    ModelAlignment ma;
    ma.kind = options.models[m];
    try {
      if (align.method == AlignMethod::best_fit) ma.motion = best_fit(pts);
      if (align.method == AlignMethod::datums) ma.motion = datum_alignment(pts, datums);
    } catch (const AlignmentError& e) {
      SourceLocation where;
      where.file = file;
      where.field = align.method == AlignMethod::datums ? "--datum-*" : "--align";
      throw InputError(where, std::string("cannot align the part: ") + e.what());
    }
    ma.rotation_urad = ma.motion.rotation_urad();
    ma.centroid_shift_um = aligned_deviation_um(ma.motion, centroid, Eigen::Vector3d::Zero());
    for (std::size_t i : part) {
      const Eigen::Vector3d& e = devs[m][i].e_um;
      ma.absolute.add(e, e.norm(), stored[i].line);
      const Eigen::Vector3d r = aligned_deviation_um(ma.motion, stored[i].point.p, e);
      ma.aligned.add(r, r.norm(), stored[i].line);
    }
    a.models.push_back(ma);
  }

  if (sink) {
    std::vector<model::Deviation> row_devs(options.models.size());
    std::vector<double> row_norms(options.models.size());
    std::vector<Eigen::Vector3d> row_aligned(options.models.size());
    for (std::size_t i = 0; i < stored.size(); ++i) {
      for (std::size_t m = 0; m < options.models.size(); ++m) {
        row_devs[m] = devs[m][i];
        row_norms[m] = norms[m][i];
        row_aligned[m] =
            aligned_deviation_um(a.models[m].motion, stored[i].point.p, devs[m][i].e_um);
      }
      sink(stored[i].point, stored[i].line, row_devs, row_norms, row_aligned);
    }
  }
  return out;
}

std::string summary_json(const AlignedPrediction& prediction) {
  nlohmann::json j = nlohmann::json::parse(summary_json(prediction.summary));
  const PartAlignmentSummary& a = prediction.alignment;
  nlohmann::json al;
  al["method"] = to_string(a.method);
  al["part_points"] = a.part_points;
  if (a.method == AlignMethod::datums)
    al["datum_points"] = {{"primary", a.datum_points[0]},
                          {"secondary", a.datum_points[1]},
                          {"tertiary", a.datum_points[2]}};
  al["models"] = nlohmann::json::array();
  for (const ModelAlignment& m : a.models)
    al["models"].push_back({{"model", model::to_string(m.kind)},
                            {"rotation_urad", vec_json(m.rotation_urad)},
                            {"centroid_shift_um", vec_json(m.centroid_shift_um)},
                            {"absolute", stats_json(m.absolute)},
                            {"aligned", stats_json(m.aligned)}});
  j["alignment"] = al;
  return j.dump(2);
}

std::string summary_table(const AlignedPrediction& prediction) {
  std::string text = summary_table(prediction.summary);
  const PartAlignmentSummary& a = prediction.alignment;
  text +=
      fmt::format("part ({} cutting points), aligned by {}", a.part_points, to_string(a.method));
  if (a.method == AlignMethod::datums)
    text += fmt::format(" (primary {}, secondary {}, tertiary {} points)", a.datum_points[0],
                        a.datum_points[1], a.datum_points[2]);
  text += ":\n";
  text += fmt::format("  {:<7} {:<8} {:>10} {:>10} {:>10} {:>10} {:>10}\n", "model", "",
                      "max|dx| µm", "max|dy| µm", "max|dz| µm", "rms|d| µm", "max|d| µm");
  auto row = [&](const char* model, const char* what, const ModelStats& s) {
    text += fmt::format("  {:<7} {:<8} {:>10.4f} {:>10.4f} {:>10.4f} {:>10.4f} {:>10.4f}\n", model,
                        what, s.max_abs_um.x(), s.max_abs_um.y(), s.max_abs_um.z(), s.rms_um(),
                        s.max_um);
  };
  for (const ModelAlignment& m : a.models) {
    row(model::to_string(m.kind), "absolute", m.absolute);
    row("", "aligned", m.aligned);
    text += fmt::format(
        "  {:<7} {:<8} rotation ({:.3f}, {:.3f}, {:.3f}) µrad, centroid shift "
        "({:.4f}, {:.4f}, {:.4f}) µm\n",
        "", "setup", m.rotation_urad.x(), m.rotation_urad.y(), m.rotation_urad.z(),
        m.centroid_shift_um.x(), m.centroid_shift_um.y(), m.centroid_shift_um.z());
  }
  return text;
}

}  // namespace abbe::pipeline
