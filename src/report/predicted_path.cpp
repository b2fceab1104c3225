#include "abbe/report/predicted_path.hpp"

#include <algorithm>
#include <sstream>

#include "abbe/io/sha256.hpp"
#include "abbe/pipeline/interpreter_setup.hpp"
#include "abbe/pipeline/model_set.hpp"
#include "abbe/pipeline/program_path.hpp"

namespace abbe::report {
namespace {

// One kept point.
struct Kept {
  std::size_t index = 0;
  Eigen::Vector3d p;
  std::size_t line = 0;
  bool rapid = false;
  double length = 0.0;
  std::vector<Eigen::Vector3d> d;  // per model
  double norm(std::size_t m) const { return d[m].norm(); }
};

// A stretch of `stride` points: its first point and, per model, the point
// of the largest |d| among the others.
struct Bucket {
  Kept regular;
  std::vector<Kept> extreme;  // per model; empty d: none yet
};

void offer(Bucket& b, const Kept& k) {
  if (b.extreme.size() < k.d.size()) b.extreme.resize(k.d.size());
  for (std::size_t m = 0; m < k.d.size(); ++m)
    if (b.extreme[m].d.empty() || k.norm(m) > b.extreme[m].norm(m)) b.extreme[m] = k;
}

// Merges the buckets pairwise (stride doubles): the first regular point
// stays, the largest of the rest per model become the extremes.
void thin(std::vector<Bucket>& buckets) {
  std::size_t j = 0;
  for (std::size_t i = 0; i < buckets.size(); i += 2) {
    Bucket b = std::move(buckets[i]);
    if (i + 1 < buckets.size()) {
      const Bucket& c = buckets[i + 1];
      offer(b, c.regular);
      for (const Kept& e : c.extreme)
        if (!e.d.empty()) offer(b, e);
    }
    buckets[j++] = std::move(b);
  }
  buckets.resize(j);
}

void append(PredictedPath& r, const Kept& k) {
  r.index.push_back(k.index);
  r.nominal.push_back(k.p);
  r.line.push_back(k.line);
  r.rapid.push_back(k.rapid);
  r.path_length.push_back(k.length);
  for (std::size_t m = 0; m < k.d.size(); ++m) r.deviation_um[m].push_back(k.d[m]);
}

// Picks the kept points out of a second prediction of every point: their
// indices ascend, so one counter walks both.
class KeptPoints {
 public:
  explicit KeptPoints(const std::vector<std::size_t>& index) : index_(index) {}
  // Whether the next point of the second prediction is a kept one.
  bool next() {
    const bool kept = kept_ < index_.size() && index_[kept_] == point_;
    ++point_;
    if (kept) ++kept_;
    return kept;
  }

 private:
  const std::vector<std::size_t>& index_;
  std::size_t point_ = 0, kept_ = 0;
};

void push_all(std::vector<std::vector<Eigen::Vector3d>>& to,
              const std::vector<Eigen::Vector3d>& values) {
  for (std::size_t m = 0; m < values.size(); ++m) to[m].push_back(values[m]);
}

// The u and the deviation after alignment of the kept points, and the
// uncertainty of the summary figures and the set-up: the program predicted
// again with the draws (predict_with_uncertainty) and/or the part's set-up
// (predict_aligned).
void add_second_pass(PredictedPath& r, const machine::Machine& machine, const std::string& text,
                     const pipeline::PathOptions& path, const PredictPathOptions& o) {
  pipeline::PredictOptions po;
  po.models = o.models;
  po.input = pipeline::PredictInput::program;
  po.path = path;
  pipeline::UncertaintyOptions uo;
  uo.draws = o.uncertainty_draws;
  uo.seed = o.seed;
  const bool aligned = o.align.method != pipeline::AlignMethod::none;
  const bool uncertain = o.uncertainty_draws > 0;
  if (uncertain) r.u_um.assign(o.models.size(), {});
  if (aligned) r.aligned_um.assign(o.models.size(), {});
  if (aligned && uncertain) r.u_aligned_um.assign(o.models.size(), {});
  std::istringstream program(text);
  KeptPoints kept(r.index);
  if (!aligned) {
    r.uncertainty =
        pipeline::predict_with_uncertainty(
            program, r.program, machine, po, uo, {},
            [&](const model::EvalPoint&, std::size_t, const std::vector<model::Deviation>&,
                const std::vector<double>&, const std::vector<Eigen::Vector3d>& u) {
              if (kept.next()) push_all(r.u_um, u);
            })
            .uncertainty;
  } else if (!uncertain) {
    r.alignment =
        pipeline::predict_aligned(
            program, r.program, machine, po, o.align, {},
            [&](const model::EvalPoint&, std::size_t, const std::vector<model::Deviation>&,
                const std::vector<double>&, const std::vector<Eigen::Vector3d>& a) {
              if (kept.next()) push_all(r.aligned_um, a);
            })
            .alignment;
  } else {
    pipeline::UncertainPrediction p = pipeline::predict_with_uncertainty(
        program, r.program, machine, po, uo, o.align, {},
        [&](const model::EvalPoint&, std::size_t, const std::vector<model::Deviation>&,
            const std::vector<double>&, const std::vector<Eigen::Vector3d>& a,
            const std::vector<Eigen::Vector3d>& u, const std::vector<Eigen::Vector3d>& ua) {
          if (!kept.next()) return;
          push_all(r.aligned_um, a);
          push_all(r.u_um, u);
          push_all(r.u_aligned_um, ua);
        });
    r.uncertainty = std::move(p.uncertainty);
    r.alignment = std::move(p.alignment);
  }
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
  r.sha256 = io::sha256_hex(text);

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
  std::vector<Bucket> buckets;
  pipeline::run_path(program, file, pipeline::interpreter_config(machine), po,
                     [&](const path::PathPoint& pp) {
                       const bool rapid = pp.kind == gcode::MotionKind::rapid;
                       models.evaluate(pipeline::eval_point(pp), file, pp.line, rapid);
                       if (r.total_points > 0) length += (pp.p - previous).norm();
                       previous = pp.p;
                       Kept k;
                       k.index = r.total_points;
                       k.p = pp.p;
                       k.line = pp.line;
                       k.rapid = rapid;
                       k.length = length;
                       k.d.resize(models.size());
                       for (std::size_t i = 0; i < models.size(); ++i)
                         k.d[i] = models.deviations()[i].e_um;
                       if (r.total_points % r.stride == 0) {
                         if (buckets.size() >= max_points) {
                           thin(buckets);
                           r.stride *= 2;
                         }
                       }
                       if (r.total_points % r.stride == 0) {
                         buckets.emplace_back().regular = std::move(k);
                       } else {
                         offer(buckets.back(), k);
                       }
                       ++r.total_points;
                       if (o.progress && (r.total_points & 1023) == 0) {
                         const auto pos = program.tellg();
                         if (pos >= 0) o.progress(static_cast<std::uint64_t>(pos));
                       }
                     });
  if (o.progress) o.progress(text.size());
  // Each stretch: its first point, then (in path order, once each) the
  // points of a model's largest |d| that exceed that model's |d| there.
  for (const Bucket& b : buckets) {
    append(r, b.regular);
    std::vector<const Kept*> extra;
    for (std::size_t m = 0; m < b.extreme.size(); ++m) {
      const Kept& e = b.extreme[m];
      if (e.d.empty() || !(e.norm(m) > b.regular.norm(m))) continue;
      if (std::none_of(extra.begin(), extra.end(),
                       [&](const Kept* x) { return x->index == e.index; }))
        extra.push_back(&e);
    }
    std::sort(extra.begin(), extra.end(),
              [](const Kept* x, const Kept* y) { return x->index < y->index; });
    for (const Kept* e : extra) append(r, *e);
  }

  for (std::size_t i = 0; i < models.size(); ++i) {
    auto stats = [&](const pipeline::ModelStats& s) {
      ModelPathStats out;
      out.model = o.models[i];
      out.points = s.points;
      out.max_abs_um = s.max_abs_um;
      out.rms_um = s.rms_um();
      out.max_um = s.max_um;
      out.max_line = s.max_line;
      out.out_of_range_lookups = models.out_of_range_lookups(i);
      return out;
    };
    r.stats.push_back(stats(models.stats()[i]));
    r.cutting_stats.push_back(stats(models.cutting_stats()[i]));
    r.rapid_stats.push_back(stats(models.rapid_stats()[i]));
  }

  if (o.uncertainty_draws > 0 || o.align.method != pipeline::AlignMethod::none)
    add_second_pass(r, machine, text, po, o);

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
