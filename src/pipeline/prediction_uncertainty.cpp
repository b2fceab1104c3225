#include "abbe/pipeline/prediction_uncertainty.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <nlohmann/json.hpp>
#include <random>

#include "abbe/io/input_error.hpp"
#include "abbe/io/units.hpp"
#include "abbe/machine/campaign_uncertainty.hpp"
#include "abbe/pipeline/model_set.hpp"

namespace abbe::pipeline {
namespace {

// The seeded N(0, 1) deviates of the draws: std::mt19937_64 (its sequence is
// fixed by the standard) with the transform done here (Box–Muller, two
// uniforms per deviate), so a seed gives the same draws with every standard
// library.
class NormalStream {
 public:
  explicit NormalStream(std::uint64_t seed) : engine_(seed) {}
  double operator()() {
    const double u1 = 1.0 - uniform();  // (0, 1]: the log is finite
    const double u2 = uniform();
    return std::sqrt(-2.0 * std::log(u1)) * std::cos(units::kTwoPi * u2);
  }

 private:
  double uniform() { return static_cast<double>(engine_() >> 11) * 0x1.0p-53; }
  std::mt19937_64 engine_;
};

struct StoredPoint {
  model::EvalPoint point;
  std::size_t line = 0;
  bool rapid = false;
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
  if (!machine::has_campaign_uncertainty(machine)) {
    SourceLocation where;
    where.file = machine.spec().file;
    where.field = "uncertainty";
    throw InputError(where,
                     "--uncertainty: nothing to propagate: the machine file gives no uncertainty "
                     "of its campaign (no `uncertainty` key, and the component table has no "
                     "`uncertainty` column; docs/formats.md)");
  }
  if (uncertainty.draws < 2) throw std::invalid_argument("--uncertainty needs at least 2 draws");

  // The plain prediction, walked once; the points are kept for the draws.
  std::vector<StoredPoint> stored;
  const std::size_t n_models = options.models.size();
  std::vector<std::vector<model::Deviation>> devs(n_models);
  std::vector<std::vector<double>> norms(n_models);
  std::size_t rapid_before = 0;
  UncertainPrediction out;
  out.summary = predict(in, file, machine, options,
                        [&](const model::EvalPoint& p, std::size_t line, const ModelSet& models) {
                          // A rapid point is the one the rapid statistics counted.
                          const std::size_t rapid_now = models.rapid_stats().front().points;
                          stored.push_back({p, line, rapid_now != rapid_before});
                          rapid_before = rapid_now;
                          for (std::size_t m = 0; m < n_models; ++m) {
                            devs[m].push_back(models.deviations()[m]);
                            norms[m].push_back(models.norms_um()[m]);
                          }
                          if (progress) progress(p, line, models);
                        });

  // The draws: per point and model, Σδ and Σδ² of δ = e_draw − e (µm); per
  // model and group, the figures of every draw.
  const std::size_t n_points = stored.size();
  std::vector<Eigen::Vector3d> sum(n_points * n_models, Eigen::Vector3d::Zero());
  std::vector<Eigen::Vector3d> sum2(n_points * n_models, Eigen::Vector3d::Zero());
  using Figures = std::array<double, kUncertainFigures>;
  std::vector<std::vector<Figures>> fig_all(n_models), fig_cut(n_models), fig_rapid(n_models);
  NormalStream normal(uncertainty.seed);
  const std::function<double()> deviate = [&normal] { return normal(); };
  for (std::size_t d = 0; d < uncertainty.draws; ++d) {
    const machine::Machine drawn = machine::draw_campaign(machine, deviate);
    ModelSet models(drawn, options.models, options.extension);
    for (std::size_t i = 0; i < n_points; ++i) {
      const StoredPoint& sp = stored[i];
      models.evaluate(sp.point, file, sp.line, sp.rapid);
      for (std::size_t m = 0; m < n_models; ++m) {
        const Eigen::Vector3d delta = models.deviations()[m].e_um - devs[m][i].e_um;
        sum[i * n_models + m] += delta;
        sum2[i * n_models + m] += delta.cwiseProduct(delta);
      }
    }
    for (std::size_t m = 0; m < n_models; ++m) {
      fig_all[m].push_back(figures_of(models.stats()[m]));
      fig_cut[m].push_back(figures_of(models.cutting_stats()[m]));
      fig_rapid[m].push_back(figures_of(models.rapid_stats()[m]));
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
    pu.models.push_back(mu);
  }

  if (sink) {
    const double n = static_cast<double>(uncertainty.draws);
    std::vector<model::Deviation> row_devs(n_models);
    std::vector<double> row_norms(n_models);
    std::vector<Eigen::Vector3d> row_u(n_models);
    for (std::size_t i = 0; i < n_points; ++i) {
      for (std::size_t m = 0; m < n_models; ++m) {
        row_devs[m] = devs[m][i];
        row_norms[m] = norms[m][i];
        const Eigen::Vector3d& s = sum[i * n_models + m];
        const Eigen::Vector3d var = (sum2[i * n_models + m] - s.cwiseProduct(s) / n) / (n - 1.0);
        row_u[m] = var.cwiseMax(0.0).cwiseSqrt();
      }
      sink(stored[i].point, stored[i].line, row_devs, row_norms, row_u);
    }
  }
  return out;
}

std::string summary_json(const UncertainPrediction& prediction) {
  nlohmann::json j = nlohmann::json::parse(summary_json(prediction.summary));
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
    u["models"].push_back(jm);
  }
  j["uncertainty"] = u;
  return j.dump(2);
}

std::string summary_table(const UncertainPrediction& prediction) {
  std::string text = summary_table(prediction.summary);
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
  }
  return text;
}

}  // namespace abbe::pipeline
