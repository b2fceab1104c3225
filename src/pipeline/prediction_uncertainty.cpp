#include "abbe/pipeline/prediction_uncertainty.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <nlohmann/json.hpp>
#include <optional>

#include "abbe/machine/campaign_uncertainty.hpp"
#include "abbe/machine/normal_stream.hpp"
#include "abbe/pipeline/model_set.hpp"
#include "abbe/pipeline/stored_prediction.hpp"

namespace abbe::pipeline {
namespace {

// Σδ and Σδ² of a point's deviation over the draws (δ about the plain
// prediction: no cancellation), and its standard deviation.
struct Moments {
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  Eigen::Vector3d sum2 = Eigen::Vector3d::Zero();
  void add(const Eigen::Vector3d& delta) {
    sum += delta;
    sum2 += delta.cwiseProduct(delta);
  }
  Eigen::Vector3d u(std::size_t draws) const {
    const double n = static_cast<double>(draws);
    const Eigen::Vector3d var = (sum2 - sum.cwiseProduct(sum) / n) / (n - 1.0);
    return var.cwiseMax(0.0).cwiseSqrt();
  }
};

std::array<double, kUncertainFigures> figures_of(const ModelStats& s) {
  return {s.max_abs_um.x(), s.max_abs_um.y(), s.max_abs_um.z(), s.rms_um(), s.max_um};
}

// The figures of one group over the draws: draws[d][f].
GroupUncertainty group_uncertainty(const ModelStats& plain,
                                   const std::vector<std::array<double, kUncertainFigures>>& draws,
                                   double k) {
  GroupUncertainty g;
  g.points = plain.points;
  const std::array<double, kUncertainFigures> value = figures_of(plain);
  const std::size_t n = draws.size();
  std::vector<double> x(n);
  for (std::size_t f = 0; f < kUncertainFigures; ++f) {
    FigureUncertainty& fu = g.figures[f];
    fu.value = value[f];
    double sum = 0.0, sum2 = 0.0;
    for (std::size_t d = 0; d < n; ++d) {
      x[d] = draws[d][f];
      const double delta = x[d] - value[f];  // about the estimate: no cancellation
      sum += delta;
      sum2 += delta * delta;
    }
    if (n >= 2) {
      const double var = (sum2 - sum * sum / static_cast<double>(n)) / static_cast<double>(n - 1);
      fu.u = std::sqrt(std::max(var, 0.0));
    }
    fu.expanded = k * fu.u;
    std::sort(x.begin(), x.end());
    if (n > 0) {
      const auto lo = static_cast<std::size_t>(std::floor(0.025 * static_cast<double>(n)));
      const auto hi = static_cast<std::size_t>(std::ceil(0.975 * static_cast<double>(n)));
      fu.low = x[std::min(lo, n - 1)];
      fu.high = x[std::min(hi > 0 ? hi - 1 : 0, n - 1)];
    }
  }
  return g;
}

const char* const kFigureKeys[kUncertainFigures] = {"max_abs_dx_um", "max_abs_dy_um",
                                                    "max_abs_dz_um", "rms_d_um", "max_d_um"};

nlohmann::json group_json(const GroupUncertainty& g) {
  nlohmann::json j;
  j["points"] = g.points;
  for (std::size_t f = 0; f < kUncertainFigures; ++f) {
    const FigureUncertainty& fu = g.figures[f];
    j[kFigureKeys[f]] = {
        {"value", fu.value}, {"u", fu.u}, {"U", fu.expanded}, {"interval_95", {fu.low, fu.high}}};
  }
  return j;
}

}  // namespace

UncertainPrediction predict_with_uncertainty(std::istream& in, const std::string& file,
                                             const machine::Machine& machine,
                                             const PredictOptions& options,
                                             const UncertaintyOptions& uncertainty,
                                             const PredictionSink& progress,
                                             const UncertainSink& sink,
                                             const std::function<void(std::size_t)>& draw_done) {
  AlignedUncertainSink aligned_sink;
  if (sink)
    aligned_sink = [&sink](const model::EvalPoint& p, std::size_t line,
                           const std::vector<model::Deviation>& devs,
                           const std::vector<double>& norms, const std::vector<Eigen::Vector3d>&,
                           const std::vector<Eigen::Vector3d>& u,
                           const std::vector<Eigen::Vector3d>&) { sink(p, line, devs, norms, u); };
  return predict_with_uncertainty(in, file, machine, options, uncertainty, AlignOptions{}, progress,
                                  aligned_sink, draw_done);
}

UncertainPrediction predict_with_uncertainty(
    std::istream& in, const std::string& file, const machine::Machine& machine,
    const PredictOptions& options, const UncertaintyOptions& uncertainty, const AlignOptions& align,
    const PredictionSink& progress, const AlignedUncertainSink& sink,
    const std::function<void(std::size_t)>& draw_done) {
  machine::require_campaign_uncertainty(machine, "--uncertainty");
  if (uncertainty.draws < 2) throw std::invalid_argument("--uncertainty needs at least 2 draws");

  // The plain prediction, walked once; the points are kept for the draws.
  UncertainPrediction out;
  const StoredPrediction stored = predict_stored(in, file, machine, options, progress);
  out.summary = stored.summary;
  const std::size_t n_models = options.models.size();
  const std::size_t n_points = stored.size();

  // The part's set-up of the plain prediction, and its deviations after it.
  const bool aligned = align.method != AlignMethod::none;
  std::optional<PartSetup> setup;
  std::vector<std::vector<Eigen::Vector3d>> plain_aligned(n_models);
  if (aligned) {
    setup.emplace(stored, align, file);
    out.alignment = setup->summary();
    for (std::size_t m = 0; m < n_models; ++m) {
      out.alignment.models.push_back(setup->align(options.models[m], deviations_um(stored, m)));
      const RigidMotion& motion = out.alignment.models[m].motion;
      plain_aligned[m].resize(n_points);
      for (std::size_t i = 0; i < n_points; ++i)
        plain_aligned[m][i] =
            aligned_deviation_um(motion, stored.points[i].p, stored.devs[m][i].e_um);
    }
  }

  // The draws: per point and model, the moments of δ = e_draw − e (and of the
  // deviation after the draw's own set-up minus the plain one); per model and
  // group, the figures of every draw.
  std::vector<Moments> absolute(n_points * n_models), after(aligned ? n_points * n_models : 0);
  using Figures = std::array<double, kUncertainFigures>;
  std::vector<std::vector<Figures>> fig_all(n_models), fig_cut(n_models), fig_rapid(n_models),
      fig_aligned(n_models);
  std::vector<std::vector<Eigen::Vector3d>> drawn_e(
      aligned ? n_models : 0, std::vector<Eigen::Vector3d>(n_points, Eigen::Vector3d::Zero()));
  machine::NormalStream normal(uncertainty.seed);
  const std::function<double()> deviate = [&normal] { return normal(); };
  for (std::size_t d = 0; d < uncertainty.draws; ++d) {
    const machine::Machine drawn = machine::draw_campaign(machine, deviate);
    ModelSet models(drawn, options.models, options.extension);
    for (std::size_t i = 0; i < n_points; ++i) {
      models.evaluate(stored.points[i], file, stored.lines[i], stored.rapid[i]);
      for (std::size_t m = 0; m < n_models; ++m) {
        const Eigen::Vector3d& e = models.deviations()[m].e_um;
        absolute[i * n_models + m].add(e - stored.devs[m][i].e_um);
        if (aligned) drawn_e[m][i] = e;
      }
    }
    for (std::size_t m = 0; m < n_models; ++m) {
      fig_all[m].push_back(figures_of(models.stats()[m]));
      fig_cut[m].push_back(figures_of(models.cutting_stats()[m]));
      fig_rapid[m].push_back(figures_of(models.rapid_stats()[m]));
      if (!aligned) continue;
      const ModelAlignment a = setup->align(options.models[m], drawn_e[m]);
      fig_aligned[m].push_back(figures_of(a.aligned));
      for (std::size_t i = 0; i < n_points; ++i)
        after[i * n_models + m].add(
            aligned_deviation_um(a.motion, stored.points[i].p, drawn_e[m][i]) -
            plain_aligned[m][i]);
    }
    if (draw_done) draw_done(d + 1);
  }

  PredictionUncertainty& pu = out.uncertainty;
  pu.draws = uncertainty.draws;
  pu.seed = uncertainty.seed;
  pu.coverage_factor = uncertainty.coverage_factor;
  pu.sources = machine::campaign_uncertainty_text(machine);
  for (std::size_t m = 0; m < n_models; ++m) {
    ModelUncertainty mu;
    mu.kind = options.models[m];
    const ModelSummary& ms = out.summary.models[m];
    mu.all = group_uncertainty(ms.stats, fig_all[m], pu.coverage_factor);
    mu.cutting = group_uncertainty(ms.cutting, fig_cut[m], pu.coverage_factor);
    mu.rapid = group_uncertainty(ms.rapid, fig_rapid[m], pu.coverage_factor);
    if (aligned)
      mu.aligned =
          group_uncertainty(out.alignment.models[m].aligned, fig_aligned[m], pu.coverage_factor);
    pu.models.push_back(mu);
  }

  if (sink) {
    const std::size_t n = uncertainty.draws;
    std::vector<Eigen::Vector3d> row_aligned(n_models, Eigen::Vector3d::Zero());
    std::vector<Eigen::Vector3d> row_u(n_models), row_u_aligned(n_models, Eigen::Vector3d::Zero());
    stored.for_each([&](std::size_t i, const std::vector<model::Deviation>& devs,
                        const std::vector<double>& norms) {
      for (std::size_t m = 0; m < n_models; ++m) {
        row_u[m] = absolute[i * n_models + m].u(n);
        if (!aligned) continue;
        row_aligned[m] = plain_aligned[m][i];
        row_u_aligned[m] = after[i * n_models + m].u(n);
      }
      sink(stored.points[i], stored.lines[i], devs, norms, row_aligned, row_u, row_u_aligned);
    });
  }
  return out;
}

std::string summary_json(const UncertainPrediction& prediction) {
  const bool aligned = prediction.alignment.method != AlignMethod::none;
  nlohmann::json j = nlohmann::json::parse(
      aligned ? summary_json(AlignedPrediction{prediction.summary, prediction.alignment})
              : summary_json(prediction.summary));
  const PredictionUncertainty& pu = prediction.uncertainty;
  nlohmann::json u;
  u["method"] = "Monte Carlo (GUM Supplement 1)";
  u["draws"] = pu.draws;
  u["seed"] = pu.seed;
  u["coverage_factor"] = pu.coverage_factor;
  u["sources"] = pu.sources;
  u["models"] = nlohmann::json::array();
  for (const ModelUncertainty& m : pu.models) {
    nlohmann::json jm;
    jm["model"] = model::to_string(m.kind);
    jm["all"] = group_json(m.all);
    if (prediction.summary.moves) {
      jm["cutting"] = group_json(m.cutting);
      jm["rapid"] = group_json(m.rapid);
    }
    if (aligned) jm["aligned"] = group_json(m.aligned);
    u["models"].push_back(jm);
  }
  j["uncertainty"] = u;
  return j.dump(2);
}

std::string summary_table(const UncertainPrediction& prediction) {
  const bool aligned = prediction.alignment.method != AlignMethod::none;
  std::string text =
      aligned ? summary_table(AlignedPrediction{prediction.summary, prediction.alignment})
              : summary_table(prediction.summary);
  const PredictionUncertainty& pu = prediction.uncertainty;
  text += fmt::format(
      "uncertainty (Monte Carlo, GUM Supplement 1: {} draws, seed {}): value ± U, U = k·u with "
      "k = {:g}\n  propagated: {}\n",
      pu.draws, pu.seed, pu.coverage_factor, pu.sources);
  text += fmt::format("  {:<7} {:<8} {:>19} {:>19} {:>19} {:>19} {:>19}\n", "model", "moves",
                      "max|dx| µm", "max|dy| µm", "max|dz| µm", "rms|d| µm", "max|d| µm");
  auto row = [&](const char* model, const char* what, const GroupUncertainty& g) {
    text += fmt::format("  {:<7} {:<8}", model, what);
    for (const FigureUncertainty& f : g.figures)
      text += fmt::format(" {:>19}", fmt::format("{:.4f} ± {:.4f}", f.value, f.expanded));
    text += "\n";
  };
  for (const ModelUncertainty& m : pu.models) {
    const char* name = model::to_string(m.kind);
    if (prediction.summary.moves) {
      row(name, "cutting", m.cutting);
      row("", "rapid", m.rapid);
      row("", "all", m.all);
    } else {
      row(name, "all", m.all);
    }
    if (aligned) row("", "aligned", m.aligned);
  }
  return text;
}

}  // namespace abbe::pipeline
