#include "abbe/pipeline/aligned_prediction.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <utility>

#include "abbe/io/input_error.hpp"
#include "abbe/io/units.hpp"

namespace abbe::pipeline {
namespace {

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

PartSetup::PartSetup(const StoredPrediction& stored, const AlignOptions& align, std::string file)
    : stored_(stored), method_(align.method), file_(std::move(file)) {
  for (std::size_t i = 0; i < stored.size(); ++i) {
    if (stored.rapid[i]) continue;
    const std::size_t k = part_.size();
    part_.push_back(i);
    centroid_ += stored.points[i].p;
    if (method_ != AlignMethod::datums) continue;
    const std::size_t line = stored.lines[i];
    if (align.primary.contains(line)) datums_.primary.push_back(k);
    if (align.secondary.contains(line)) datums_.secondary.push_back(k);
    if (align.tertiary.contains(line)) datums_.tertiary.push_back(k);
  }
  if (!part_.empty()) centroid_ /= static_cast<double>(part_.size());
}

PartAlignmentSummary PartSetup::summary() const {
  PartAlignmentSummary a;
  a.method = method_;
  a.part_points = part_.size();
  a.datum_points[0] = datums_.primary.size();
  a.datum_points[1] = datums_.secondary.size();
  a.datum_points[2] = datums_.tertiary.size();
  return a;
}

ModelAlignment PartSetup::align(model::ModelKind kind,
                                const std::vector<Eigen::Vector3d>& e_um) const {
  PartPoints pts;
  for (std::size_t i : part_) pts.add(stored_.points[i].p, e_um[i]);
  ModelAlignment ma;
  ma.kind = kind;
  try {
    if (method_ == AlignMethod::best_fit) ma.motion = best_fit(pts);
    if (method_ == AlignMethod::datums) ma.motion = datum_alignment(pts, datums_);
  } catch (const AlignmentError& e) {
    SourceLocation where;
    where.file = file_;
    where.field = method_ == AlignMethod::datums ? "--datum-*" : "--align";
    throw InputError(where, std::string("cannot align the part: ") + e.what());
  }
  ma.rotation_urad = ma.motion.rotation_urad();
  ma.centroid_shift_um = aligned_deviation_um(ma.motion, centroid_, Eigen::Vector3d::Zero());
  for (std::size_t i : part_) {
    const Eigen::Vector3d& e = e_um[i];
    ma.absolute.add(e, e.norm(), stored_.lines[i]);
    const Eigen::Vector3d r = aligned_deviation_um(ma.motion, stored_.points[i].p, e);
    ma.aligned.add(r, r.norm(), stored_.lines[i]);
  }
  return ma;
}

std::vector<Eigen::Vector3d> deviations_um(const StoredPrediction& stored, std::size_t m) {
  std::vector<Eigen::Vector3d> e(stored.size());
  for (std::size_t i = 0; i < e.size(); ++i) e[i] = stored.devs[m][i].e_um;
  return e;
}

AlignedPrediction predict_aligned(std::istream& in, const std::string& file,
                                  const machine::Machine& machine, const PredictOptions& options,
                                  const AlignOptions& align, const PredictionSink& progress,
                                  const AlignedSink& sink) {
  const StoredPrediction stored = predict_stored(in, file, machine, options, progress);
  const PartSetup setup(stored, align, file);
  AlignedPrediction out;
  out.summary = stored.summary;
  out.alignment = setup.summary();
  for (std::size_t m = 0; m < options.models.size(); ++m)
    out.alignment.models.push_back(setup.align(options.models[m], deviations_um(stored, m)));
  if (sink) {
    std::vector<Eigen::Vector3d> row_aligned(options.models.size());
    stored.for_each([&](std::size_t i, const std::vector<model::Deviation>& devs,
                        const std::vector<double>& norms) {
      for (std::size_t m = 0; m < devs.size(); ++m)
        row_aligned[m] =
            aligned_deviation_um(out.alignment.models[m].motion, stored.points[i].p, devs[m].e_um);
      sink(stored.points[i], stored.lines[i], devs, norms, row_aligned);
    });
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
