#include "abbe/diagnose/table_uncertainty.hpp"

#include <Eigen/Cholesky>
#include <cmath>
#include <functional>
#include <stdexcept>

#include "abbe/machine/campaign_uncertainty.hpp"
#include "abbe/machine/normal_stream.hpp"
#include "abbe/model/error_model.hpp"
#include "searched_uncertainty.hpp"

namespace abbe::diagnose {
namespace {

using Mat = Eigen::MatrixXd;
using Vec = Eigen::VectorXd;

// One refitted term: where its coefficients and (searched_col ≥ 0) the
// derivative in its searched parameter sit among the columns.
struct Refitted {
  SelectedTerm* st = nullptr;
  Eigen::Index first = 0, k = 0;
  Eigen::Index searched_col = -1;
};

}  // namespace

TableUncertainty add_table_uncertainty(const machine::Machine& machine,
                                       const io::MeasuredData& data, model::ModelKind model,
                                       const Problem& fitted,
                                       const std::vector<std::uint32_t>& dropped, std::size_t draws,
                                       std::uint64_t seed, std::vector<SelectedTerm>& datum,
                                       std::vector<SelectedTerm>& effects) {
  machine::require_campaign_uncertainty(machine, "--table-uncertainty");
  if (draws < 2) throw std::invalid_argument("--table-uncertainty needs at least 2 draws");
  TableUncertainty out;
  out.available = true;  // require_campaign_uncertainty passed
  out.draws = draws;
  out.seed = seed;
  out.sources = machine::campaign_uncertainty_text(machine);
  const Eigen::Index n = fitted.y.size();

  // The columns of the final fit's first stage (datum and named effects),
  // each searched parameter's derivative beside them: the joint
  // linearisation of the fit in every parameter.
  std::vector<Refitted> refit;
  std::vector<Mat> blocks;
  Eigen::Index P = 0;
  for (auto* list : {&datum, &effects})
    for (SelectedTerm& st : *list) {
      if (st.term.kind == TermKind::unexplained || st.term.coef.empty()) continue;
      Refitted r;
      r.st = &st;
      blocks.push_back(term_columns(fitted, st.term));
      r.first = P;
      r.k = blocks.back().cols();
      P += r.k;
      refit.push_back(r);
    }
  for (Refitted& r : refit) {
    if (!std::isfinite(r.st->term.searched_stderr)) continue;  // nothing fixes θ
    Vec d = selection::searched_derivative(fitted, r.st->term);
    if (d.size() == 0) continue;
    blocks.emplace_back(d);
    r.searched_col = P++;
  }
  if (P == 0) return out;
  Mat A(n, P);
  {
    Eigen::Index c = 0;
    for (const Mat& b : blocks) {
      A.middleCols(c, b.cols()) = b;
      c += b.cols();
    }
  }
  Mat AtA = A.transpose() * A;
  AtA.diagonal().array() += 1e-12 * AtA.trace() / static_cast<double>(P);
  const Eigen::LDLT<Mat> ldlt(AtA);

  // The fitted points (one per row of the data, less the dropped ones, in
  // order) as the model evaluates them.
  std::vector<model::EvalPoint> points;
  points.reserve(fitted.points.size());
  for (std::size_t row = 0, next = 0; row < data.rows.size(); ++row) {
    if (next < dropped.size() && dropped[next] == row) {
      ++next;
      continue;
    }
    const io::MeasuredRow& r = data.rows[row];
    model::EvalPoint ep;
    ep.p = r.p;
    ep.tool_length = r.tool_length_or(machine.tool_length());
    ep.dir = r.v;
    ep.time = r.t;
    points.push_back(ep);
  }
  // The base model's prediction at every point with the tables of `m`.
  auto predicted = [&](const machine::Machine& m) {
    const model::ErrorModel em(m, model);
    model::ModelData md;
    std::vector<Eigen::Vector3d> e(points.size());
    for (std::size_t i = 0; i < points.size(); ++i) e[i] = em.evaluate(points[i], md).e_um;
    return e;
  };
  const std::vector<Eigen::Vector3d> e0 = predicted(machine);

  // Σδ and Σδ² of every parameter's shift over the draws. A draw moves the
  // residual by −u·(its prediction − the nominal one) per observation (an
  // overlay given with --extend is left as fitted: its terms' dependence on
  // the model's angles is of second order).
  Vec sum = Vec::Zero(P), sum2 = Vec::Zero(P);
  Vec dy(n);
  machine::NormalStream normal(seed);
  const std::function<double()> deviate = [&normal] { return normal(); };
  for (std::size_t k = 0; k < draws; ++k) {
    const std::vector<Eigen::Vector3d> e = predicted(machine::draw_campaign(machine, deviate));
    for (Eigen::Index o = 0; o < n; ++o) {
      const Observation& ob = fitted.obs[static_cast<std::size_t>(o)];
      dy[o] = -ob.u.dot(e[ob.point] - e0[ob.point]);
    }
    const Vec shift = ldlt.solve(A.transpose() * dy);
    sum += shift;
    sum2 += shift.cwiseAbs2();
  }
  const auto N = static_cast<double>(draws);
  const Vec u = ((sum2 - sum.cwiseAbs2() / N) / (N - 1.0)).cwiseMax(0.0).cwiseSqrt();

  for (const Refitted& r : refit) {
    SelectedTerm& st = *r.st;
    st.stderr_data = st.term.stderr_;
    st.stderr_tables.assign(static_cast<std::size_t>(r.k), 0.0);
    for (Eigen::Index c = 0; c < r.k; ++c) {
      const auto i = static_cast<std::size_t>(c);
      st.stderr_tables[i] = u[r.first + c];
      if (i < st.term.stderr_.size())
        st.term.stderr_[i] = std::hypot(st.stderr_data[i], st.stderr_tables[i]);
    }
    if (r.searched_col >= 0) {
      st.searched_stderr_data = st.term.searched_stderr;
      st.searched_stderr_tables = u[r.searched_col];
      st.term.searched_stderr = std::hypot(st.searched_stderr_data, st.searched_stderr_tables);
    }
  }
  return out;
}

}  // namespace abbe::diagnose
