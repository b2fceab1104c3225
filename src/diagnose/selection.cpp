#include "abbe/diagnose/selection.hpp"

#include <fmt/format.h>

#include <Eigen/Cholesky>
#include <algorithm>
#include <array>
#include <cmath>
#include <deque>
#include <map>
#include <numeric>
#include <random>

#include "abbe/diagnose/separation.hpp"
#include "abbe/diagnose/statistics.hpp"
#include "abbe/io/units.hpp"

namespace abbe::diagnose {
namespace {

using Mat = Eigen::MatrixXd;
using Vec = Eigen::VectorXd;

struct Cached {
  Term term;
  Mat C;                        // observations × k
  Mat CtC;                      // k × k
  Mat QtC;                      // p × k, extended as Q grows
  std::vector<double> aliases;  // cyclic: other periods that fit these points as well
};

// ΔRSS of adding C to the selected span Q (r ⟂ Q). Returns −1 when C lies in
// span(Q) (nothing new to fit).
double delta_rss(const Mat& C, const Mat& CtC, const Mat& QtC, const Vec& r, Vec* beta = nullptr) {
  const Vec b = C.transpose() * r;
  Mat G = CtC;
  if (QtC.rows() > 0) G.noalias() -= QtC.transpose() * QtC;
  for (Eigen::Index c = 0; c < G.rows(); ++c)
    if (!(G(c, c) > 1e-8 * CtC(c, c)) || CtC(c, c) <= 0.0) return -1.0;
  Eigen::LDLT<Mat> ldlt(G);
  const Vec x = ldlt.solve(b);
  if (beta) *beta = x;
  return b.dot(x);
}

// Point-level sums of the current residual: R(p,·) = Σ_o u_o r_o; W(p,i) = Σ_o u_o,i².
void point_sums(const Problem& pb, const Vec& r, Mat& R, Mat& W) {
  const auto np = static_cast<Eigen::Index>(pb.points.size());
  R = Mat::Zero(np, 3);
  W = Mat::Zero(np, 3);
  for (std::size_t o = 0; o < pb.obs.size(); ++o) {
    const Observation& ob = pb.obs[o];
    const auto p = static_cast<Eigen::Index>(ob.point);
    R.row(p) += r[static_cast<Eigen::Index>(o)] * ob.u.transpose();
    W.row(p) += ob.u.cwiseAbs2().transpose();
  }
}

// Point-level basis of an unexplained term (points × k, the direction ignored).
Mat generic_basis(const Problem& pb, const Term& t) {
  Term one = t;
  one.direction = 0;
  const int k = t.columns();
  Mat B(static_cast<Eigen::Index>(pb.points.size()), k);
  Eigen::Matrix<double, 3, Eigen::Dynamic> g(3, k);
  for (std::size_t p = 0; p < pb.points.size(); ++p) {
    one.basis(pb.points[p], g);
    B.row(static_cast<Eigen::Index>(p)) = g.row(0);
  }
  return B;
}

// Σ over the observations of |g_c(point)|² (the deviation the term's
// columns make, whatever direction is measured).
double motion_squared(const Problem& pb, const Term& t) {
  const int k = t.columns();
  Eigen::Matrix<double, 3, Eigen::Dynamic> g(3, k);
  double s = 0.0;
  for (const Observation& ob : pb.obs) {
    t.basis(pb.points[ob.point], g);
    s += g.squaredNorm();
  }
  return s;
}

// |cos| of the angle between two fitted contributions.
double abs_correlation(const Vec& a, const Vec& b) {
  return std::abs(a.dot(b)) / std::max(a.norm() * b.norm(), 1e-300);
}

void append_orthonormal(Mat& Q, const Mat& C) {
  for (Eigen::Index c = 0; c < C.cols(); ++c) {
    Vec q = C.col(c);
    const double n0 = q.norm();
    for (int pass = 0; pass < 2; ++pass)
      if (Q.cols() > 0) q -= Q * (Q.transpose() * q);
    const double n = q.norm();
    if (!(n > 1e-10 * n0) || n0 == 0.0) continue;
    Q.conservativeResize(Eigen::NoChange, Q.cols() + 1);
    Q.col(Q.cols() - 1) = q / n;
  }
}

// The variables (x, y, z, t) a term's deviation is a function of; false
// for a term that is not a function of a few of them (a reversal follows the
// motion; a setup rotation or a model choice, every position).
bool within_variables(const Term& t, const std::vector<int>& vars) {
  auto has = [&](int v) { return std::find(vars.begin(), vars.end(), v) != vars.end(); };
  switch (t.kind) {
    case TermKind::scale:
    case TermKind::squareness:
    case TermKind::cyclic:
    case TermKind::arm_offset:
      return has(t.axis);
    case TermKind::coupling:
      return has(t.axis) && has(t.with_axis);
    case TermKind::thermal_drift:
      return has(3) && (t.with_axis < 0 || has(t.with_axis));
    case TermKind::reversal:  // on a serpentine walk a function of the other axes' rows
      return true;
    default:
      return false;
  }
}

// Share of the deviation a term's columns make (at unit coefficients, over
// the points) that lies along `direction`.
double share_along(const Problem& pb, const Term& t, int direction) {
  const int k = t.columns();
  Eigen::Matrix<double, 3, Eigen::Dynamic> g(3, k);
  double along = 0.0, all = 0.0;
  for (const PointContext& pc : pb.points) {
    t.basis(pc, g);
    along += g.row(direction).squaredNorm();
    all += g.squaredNorm();
  }
  return all > 0.0 ? along / all : 0.0;
}

}  // namespace

std::vector<int> point_folds(std::size_t points, int folds, std::uint64_t seed) {
  std::vector<std::size_t> order(points);
  std::iota(order.begin(), order.end(), 0);
  std::mt19937_64 rng(seed);
  std::shuffle(order.begin(), order.end(), rng);
  std::vector<int> fold(points, 0);
  for (std::size_t i = 0; i < points; ++i)
    fold[order[i]] = static_cast<int>(i % static_cast<std::size_t>(std::max(folds, 1)));
  return fold;
}

Eigen::MatrixXd term_columns(const Problem& pb, const Term& term) {
  const int k = term.columns();
  Mat C(static_cast<Eigen::Index>(pb.obs.size()), k);
  Eigen::Matrix<double, 3, Eigen::Dynamic> g(3, k);
  std::uint32_t last = UINT32_MAX;
  for (std::size_t o = 0; o < pb.obs.size(); ++o) {
    const Observation& ob = pb.obs[o];
    if (ob.point != last) {
      term.basis(pb.points[ob.point], g);
      last = ob.point;
    }
    const double u0 = ob.u[0], u1 = ob.u[1], u2 = ob.u[2];
    const double* gd = g.data();
    for (int c = 0; c < k; ++c, gd += 3)
      C(static_cast<Eigen::Index>(o), c) = u0 * gd[0] + u1 * gd[1] + u2 * gd[2];
  }
  return C;
}

double cross_validated_sse(const Problem& pb, const Eigen::MatrixXd& X, const Eigen::VectorXd& y,
                           const std::vector<int>& fold_of_point, int folds) {
  const Eigen::Index P = X.cols();
  if (P == 0) return y.squaredNorm();
  std::vector<std::vector<Eigen::Index>> rows(static_cast<std::size_t>(folds));
  for (std::size_t o = 0; o < pb.obs.size(); ++o)
    rows[static_cast<std::size_t>(fold_of_point[pb.obs[o].point])].push_back(
        static_cast<Eigen::Index>(o));
  std::vector<Mat> G(rows.size());
  std::vector<Vec> b(rows.size());
  std::vector<double> yy(rows.size());
  Mat Gt = Mat::Zero(P, P);
  Vec bt = Vec::Zero(P);
  for (std::size_t f = 0; f < rows.size(); ++f) {
    const Mat Xf = X(rows[f], Eigen::all);
    const Vec yf = y(rows[f]);
    G[f] = Xf.transpose() * Xf;
    b[f] = Xf.transpose() * yf;
    yy[f] = yf.squaredNorm();
    Gt += G[f];
    bt += b[f];
  }
  const double ridge = 1e-10 * Gt.trace() / static_cast<double>(P);
  double sse = 0.0;
  for (std::size_t f = 0; f < rows.size(); ++f) {
    if (rows[f].empty()) continue;
    Mat A = Gt - G[f];
    A.diagonal().array() += ridge;
    const Vec beta = A.ldlt().solve(bt - b[f]);
    sse += yy[f] - 2.0 * beta.dot(b[f]) + beta.dot(G[f] * beta);
  }
  return sse;
}

SelectionResult select_effects(const Problem& pb, const CandidateSet& cs,
                               const SelectionOptions& o) {
  SelectionResult res;
  const auto n = static_cast<Eigen::Index>(pb.obs.size());
  const auto np = pb.points.size();
  const Vec& y = pb.y;
  res.baseline_sse = y.squaredNorm();
  const std::vector<int> folds = point_folds(np, o.folds, o.seed);

  // Named candidates without a searched parameter: columns cached once.
  // The datum: always in the fit, before any effect.
  Mat Q(n, 0);
  Mat X(n, 0);
  std::vector<Term> chosen;
  std::vector<std::vector<std::string>> ambiguous;
  std::vector<std::string> separations;  // per chosen term: what would tell it from its rivals
  for (const Term& t : cs.datum) {
    const Mat C = term_columns(pb, t);
    // Invisible in these data: the measured directions see (almost) none of
    // what the term moves — e.g. the rotation of a circle measured along
    // its radius, seen only through the rounding of the file's numbers.
    if (!(C.squaredNorm() > 1e-6 * motion_squared(pb, t))) continue;
    const Eigen::Index before = Q.cols();
    append_orthonormal(Q, C);
    if (Q.cols() == before) continue;  // already in the span of the datum
    Mat Xn(n, X.cols() + C.cols());
    Xn << X, C;
    X = std::move(Xn);
    chosen.push_back(t);
    ambiguous.emplace_back();
    separations.emplace_back();
  }
  const std::size_t n_datum = chosen.size();
  const Mat Qd = Q;  // the datum's span
  Vec r = y - Q * (Q.transpose() * y);
  res.datum_sse = r.squaredNorm();
  double cv_prev = X.cols() > 0 ? cross_validated_sse(pb, X, y, folds, o.folds) : res.baseline_sse;
  res.datum_cv_sse = cv_prev;

  std::vector<Cached> named;
  for (const Term& t : cs.fixed) {
    Cached c{t, term_columns(pb, t), Mat(), Mat(), {}};
    c.QtC = Q.transpose() * c.C;
    c.CtC = c.C.transpose() * c.C;
    if (c.CtC.diagonal().maxCoeff() <= 0.0) continue;  // invisible in these data
    named.push_back(std::move(c));
  }
  // Smooth families: point-level Gram matrices per direction, once.
  struct Generic {
    Term term;
    std::array<Mat, 3> G;
  };
  std::vector<Generic> generic;
  {
    Mat R, W;
    point_sums(pb, y, R, W);
    for (const Term& t : cs.generic) {
      Generic g{t, {}};
      const Mat B = generic_basis(pb, t);
      for (int i = 0; i < 3; ++i)
        if (pb.direction_present[static_cast<std::size_t>(i)])
          g.G[static_cast<std::size_t>(i)] = B.transpose() * W.col(i).asDiagonal() * B;
      generic.push_back(std::move(g));
    }
  }

  // The set of each point (its index in pb.sets).
  std::vector<std::size_t> set_of(np, 0);
  for (std::size_t p = 0; p < np; ++p) {
    const auto it = std::find(pb.sets.begin(), pb.sets.end(), pb.points[p].set);
    set_of[p] = it == pb.sets.end() ? 0 : static_cast<std::size_t>(it - pb.sets.begin());
  }
  const double tests_named = std::max(cs.named_tests, 1);
  const double tests_generic = std::max(cs.generic_tests, 1);
  // Subsample for the period scan.
  const std::size_t stride = std::max<std::size_t>(1, (np + o.scan_points - 1) / o.scan_points);

  std::array<double, 64> practical_cache{};                  // by column count
  std::map<std::string, std::array<double, 3>> share_cache;  // by label: share along each direction
  for (int step = 0; step < o.max_terms; ++step) {
    if (o.on_step) o.on_step(step);
    const double rr = r.squaredNorm();
    const double dof_base = static_cast<double>(n - Q.cols());
    if (dof_base < 4.0) break;
    Mat R, W;
    point_sums(pb, r, R, W);
    // The practical floor in units of σ̂²: an effect that removes exactly
    // n·(f·σ̂)² would give ΔRSS/σ̂² ~ χ²_k(λ = n·f²) (its noise adds k and
    // scatters it); the candidate must exceed that distribution's upper α
    // quantile, so that its effect is shown above the floor, not only
    // estimated there (min_effect_test; else ΔRSS ≥ n·f²·σ̂²).
    const double lambda = static_cast<double>(n) * o.min_effect_rms * o.min_effect_rms;
    auto practical = [&](int k) {
      if (!o.min_effect_test) return lambda;
      // Cached per column count below 64 (n is fixed); a wider candidate
      // (a large smooth family) gets its own quantile.
      if (k >= static_cast<int>(practical_cache.size()))
        return noncentral_chi2_upper_quantile(k, lambda, o.alpha);
      double& q = practical_cache[static_cast<std::size_t>(k)];
      if (q <= 0.0) q = noncentral_chi2_upper_quantile(k, lambda, o.alpha);
      return q;
    };

    // Searched families: pick the parameter by a quick projection, then
    // evaluate the best of each family exactly.
    std::vector<Cached> scanned;
    std::array<std::vector<double>, 3> power_cache;  // per axis: [freq][dir][re, im]
    for (const ScanFamily& f : cs.scanned) {
      Term t = f.base;
      std::vector<double> aliases;
      if (t.kind == TermKind::cyclic) {
        const auto j = static_cast<std::size_t>(t.axis);
        auto& acc = power_cache[j];
        if (acc.empty()) {
          // Σ_p R(p,i)·exp(i2πf s_j) over the frequency grid (shared by the three directions).
          const std::size_t nf = f.grid.size();
          acc.assign(6 * nf, 0.0);
          const double f0 = 1.0 / f.grid.front();
          const double df = nf > 1 ? 1.0 / f.grid[1] - f0 : 0.0;
          for (std::size_t p = 0; p < np; p += stride) {
            const double s = pb.points[p].s[t.axis];
            // z = exp(i2πf s) stepped through the grid by the factor exp(i2π·df·s).
            double zr = std::cos(units::kTwoPi * f0 * s), zi = std::sin(units::kTwoPi * f0 * s);
            const double mr = std::cos(units::kTwoPi * df * s),
                         mi = std::sin(units::kTwoPi * df * s);
            const auto ip = static_cast<Eigen::Index>(p);
            const double r0 = R(ip, 0), r1 = R(ip, 1), r2 = R(ip, 2);
            double* a = acc.data();
            for (std::size_t q = 0; q < nf; ++q, a += 6) {
              a[0] += r0 * zr;
              a[1] += r0 * zi;
              a[2] += r1 * zr;
              a[3] += r1 * zi;
              a[4] += r2 * zr;
              a[5] += r2 * zi;
              const double nr = zr * mr - zi * mi;
              zi = zr * mi + zi * mr;
              zr = nr;
            }
          }
        }
        std::size_t best = 0;
        double best_pow = -1.0;
        std::vector<double> pow(f.grid.size());
        for (std::size_t q = 0; q < f.grid.size(); ++q) {
          const std::size_t at = 6 * q + 2 * static_cast<std::size_t>(t.direction);
          const double pw = acc[at] * acc[at] + acc[at + 1] * acc[at + 1];
          pow[q] = pw;
          if (pw > best_pow) {
            best_pow = pw;
            best = q;
          }
        }
        t.period_mm = f.grid[best];
        // The peak between the grid's frequencies: a parabola through the
        // best power and its two neighbours (a period a quarter step off
        // beats against the data over a long travel).
        if (best > 0 && best + 1 < pow.size()) {
          const double pm = pow[best - 1], p0 = pow[best], pp = pow[best + 1];
          const double curv = pm - 2.0 * p0 + pp;
          if (curv < 0.0) {
            const double delta = std::clamp(0.5 * (pm - pp) / curv, -0.5, 0.5);
            const double fb = 1.0 / f.grid[best];
            const double step = 1.0 / f.grid[best + 1] - fb;
            t.period_mm = 1.0 / (fb + delta * step);
          }
        }
        // Aliases: other peaks (local maxima away from the best) that reach
        // nearly the same power — on regularly spaced levels a period and its
        // aliases give the same samples, and the design cannot tell them apart.
        for (std::size_t q = 1; q + 1 < pow.size(); ++q) {
          const std::size_t gap = q > best ? q - best : best - q;
          if (gap <= 4 || pow[q] < pow[q - 1] || pow[q] < pow[q + 1]) continue;
          if (pow[q] >= o.alias_power * best_pow) aliases.push_back(f.grid[q]);
        }
      } else {  // thermal_drift: the time constant with the largest normalised projection
        // The residual is orthogonal to the datum's offsets, so the
        // column's norm is taken without its mean per set (else a time
        // constant whose column has the larger mean is penalised, and the
        // scan prefers the wrong shape).
        double best_score = -1.0;
        const std::size_t ns = std::max<std::size_t>(pb.sets.size(), 1);
        std::vector<double> sw(ns), swg(ns);
        for (double tau : f.grid) {
          double num = 0.0, den = 0.0;
          std::fill(sw.begin(), sw.end(), 0.0);
          std::fill(swg.begin(), swg.end(), 0.0);
          for (std::size_t p = 0; p < np; p += stride) {
            const PointContext& pc = pb.points[p];
            const double tt = std::max(pc.t, 0.0);
            double g = tau > 0.0 ? 1.0 - std::exp(-tt / tau) : tt / 3600.0;
            if (t.with_axis >= 0) g *= 1e-3 * pc.s[t.with_axis];
            const auto ip = static_cast<Eigen::Index>(p);
            const double w = W(ip, t.direction);
            num += R(ip, t.direction) * g;
            den += w * g * g;
            sw[set_of[p]] += w;
            swg[set_of[p]] += w * g;
          }
          for (std::size_t k = 0; k < ns; ++k)
            if (sw[k] > 0.0) den -= swg[k] * swg[k] / sw[k];
          const double score = den > 0.0 ? num * num / den : 0.0;
          if (score > best_score) {
            best_score = score;
            t.tau_s = tau;
          }
        }
      }
      Cached c{t, term_columns(pb, t), Mat(), Mat(), std::move(aliases)};
      c.CtC = c.C.transpose() * c.C;
      c.QtC = Q.transpose() * c.C;
      scanned.push_back(std::move(c));
    }

    // Best named candidate.
    struct Score {
      const Cached* c = nullptr;
      double d = -1.0;
      double thr = 0.0;
    };
    std::vector<Score> scores;
    auto consider = [&](const Cached& c) {
      const double d = delta_rss(c.C, c.CtC, c.QtC, r);
      if (d <= 0.0) return;
      const int k = c.term.columns();
      const double s2 = std::max(rr - d, 1e-300) / std::max(dof_base - k, 1.0);
      const double chi2 = chi2_upper_quantile(k, o.alpha / tests_named);
      scores.push_back({&c, d, s2 * std::max(chi2, practical(k))});
    };
    for (const Cached& c : named) consider(c);
    for (const Cached& c : scanned) consider(c);
    std::sort(scores.begin(), scores.end(),
              [](const Score& a, const Score& b) { return a.d > b.d; });
    // Parsimony: an information criterion that charges every column ln(n)
    // residual variances and a searched period or time constant
    // `searched_cost` columns more (a one-column squareness beats a cyclic
    // term that fits the same line only by fitting the noise).
    auto cost = [&](const Term& t) {
      const bool searched = t.kind == TermKind::cyclic || t.kind == TermKind::thermal_drift;
      return t.columns() + (searched ? o.searched_cost : 0.0);
    };
    const double ln_n = std::log(static_cast<double>(n));
    double s2_ic = rr / dof_base;
    for (const Score& s : scores)
      s2_ic = std::min(s2_ic,
                       std::max(rr - s.d, 1e-300) / std::max(dof_base - s.c->term.columns(), 1.0));
    auto ic_gain = [&](double d, double c) { return d - s2_ic * ln_n * c; };
    // The fitted contribution of a candidate (orthogonal to the selected span).
    auto contribution = [&](const Cached& c) {
      Vec beta;
      delta_rss(c.C, c.CtC, c.QtC, r, &beta);
      Vec f = c.C * beta;
      if (Q.cols() > 0) f -= Q * (c.QtC * beta);
      return f;
    };
    const Score* best_named = nullptr;
    for (const Score& s : scores)
      if (s.d > s.thr) {
        best_named = &s;
        break;
      }
    // Only explanations of the same structure compete on the criterion: a
    // cheaper candidate whose fitted contribution correlates with the
    // largest one's above `competing_corr` and has the better criterion
    // takes its place.
    if (o.parsimony_ic && best_named) {
      const Score* first = best_named;
      const Vec f0 = contribution(*first->c);
      for (const Score& s : scores) {
        if (&s == first || !(s.d > s.thr) || cost(s.c->term) >= cost(first->c->term)) continue;
        if (!(ic_gain(s.d, cost(s.c->term)) > ic_gain(best_named->d, cost(best_named->c->term))))
          continue;
        if (abs_correlation(f0, contribution(*s.c)) > o.competing_corr) best_named = &s;
      }
    }

    // Best smooth function (approximate: not orthogonalised against Q, so it
    // never overstates what it explains).
    double g_best_excess = 0.0, g_best_d = 0.0;
    Term g_best;
    bool have_generic = false;
    for (const Generic& g : generic) {
      const Mat B = generic_basis(pb, g.term);
      const Mat BtR = B.transpose() * R;
      for (int i = 0; i < 3; ++i) {
        if (!pb.direction_present[static_cast<std::size_t>(i)]) continue;
        const Mat& G = g.G[static_cast<std::size_t>(i)];
        const Vec b = BtR.col(i);
        Eigen::LDLT<Mat> ldlt(G);
        const double d = b.dot(ldlt.solve(b));
        const int k = g.term.columns();
        const double s2 = std::max(rr - d, 1e-300) / std::max(dof_base - k, 1.0);
        const double thr =
            s2 * std::max(chi2_upper_quantile(k, o.alpha / tests_generic), practical(k));
        if (d > thr && d - thr > g_best_excess) {
          g_best_excess = d - thr;
          g_best_d = d;
          g_best = g.term;
          g_best.direction = i;
          have_generic = true;
        }
      }
    }

    // Before the smooth function is taken: does a named part of its
    // structure, alone or with up to two partners, explain it as well at a
    // lower cost (docs/diagnosis.md, step 3)?
    bool combination_wins = false;
    std::vector<const Score*> partners;             // of a winning combination, beside best_named
    double d_partners = 0.0;                        // ΔRSS of the whole combination
    std::vector<std::vector<Term>> partner_rivals;  // per partner: what may stand in its place
    // ΔRSS of several candidates together (orthogonal to the selected span).
    auto together = [&](const std::vector<const Score*>& members) {
      Eigen::Index k = 0;
      for (const Score* m : members) k += m->c->C.cols();
      Mat Cj(n, k), QtCj(Q.cols(), k);
      Eigen::Index at = 0;
      for (const Score* m : members) {
        Cj.middleCols(at, m->c->C.cols()) = m->c->C;
        QtCj.middleCols(at, m->c->C.cols()) = m->c->QtC;
        at += m->c->C.cols();
      }
      const Mat CtCj = Cj.transpose() * Cj;
      return delta_rss(Cj, CtCj, QtCj, r);
    };
    // Drifts at other time constants tried in a combination (below); kept
    // for the step, a partner may point to one.
    std::deque<Cached> rescanned;
    std::deque<Score> rescanned_scores;
    // The structure the best smooth function explains: a named candidate is
    // a part of it when it is a function of its variables only, moving at
    // least half along its direction (not, e.g., an arm offset that moves X
    // and Y beside a structure in Z; a reversal counts, it follows the rows
    // of a walk).
    auto share_of = [&](const Score& sc, int direction) {
      const std::string key = sc.c->term.label();
      auto it = share_cache.find(key);
      if (it == share_cache.end()) {
        std::array<double, 3> sh{};
        for (int i = 0; i < 3; ++i)
          sh[static_cast<std::size_t>(i)] = share_along(pb, sc.c->term, i);
        it = share_cache.emplace(key, sh).first;
      }
      return it->second[static_cast<std::size_t>(direction)];
    };
    // The smooth function's fitted contribution (orthogonal to the selected span).
    auto generic_fit = [&]() {
      Mat Cg = term_columns(pb, g_best);
      if (Q.cols() > 0) Cg -= Q * (Q.transpose() * Cg);
      Mat G = Cg.transpose() * Cg;
      G.diagonal().array() += 1e-12 * std::max(G.trace(), 1e-300) / static_cast<double>(G.rows());
      const Vec beta = G.ldlt().solve(Cg.transpose() * r);
      return Vec(Cg * beta);
    };
    auto in_structure = [&](const Score& sc) {
      return have_generic && within_variables(sc.c->term, g_best.vars) &&
             share_of(sc, g_best.direction) >= 0.5;
    };
    auto significant = [&](const Score& sc) {
      const int k = sc.c->term.columns();
      const double s2 = std::max(rr - sc.d, 1e-300) / std::max(dof_base - k, 1.0);
      return sc.d > s2 * chi2_upper_quantile(k, o.alpha / tests_named);
    };
    // Where the smooth function explains more than the best named candidate
    // can: its structure is explained from the best named candidate that is
    // a part of it (or, where none passes the floors alone, the largest
    // significant part: e.g. a coupling whose linear parts take half of it),
    // alone or in a combination. The best named candidate may explain
    // another structure (two effects in the data): then, if the smooth
    // function's structure has no named explanation, the other is named
    // first and the smooth function competes again at the next step.
    const Score* lead = nullptr;
    bool other_structure = false, lead_explains = false;
    if (have_generic && (!best_named || best_named->d < o.name_ratio * g_best_d)) {
      for (const Score& sc : scores)
        if (sc.d > sc.thr && in_structure(sc)) {
          lead = &sc;
          break;
        }
      if (!lead)
        for (const Score& sc : scores)
          if (in_structure(sc)) {
            if (significant(sc)) lead = &sc;
            break;
          }
      // Another structure: the best named candidate is no part of the
      // smooth function's (another direction or other variables) and its
      // fitted contribution hardly correlates with the smooth function's (a
      // candidate of other variables may still fit the same structure: a
      // drift y·t of τ 300 s is a function of y for most of a measurement).
      other_structure =
          best_named &&
          (share_of(*best_named, g_best.direction) < 0.5 || !in_structure(*best_named)) &&
          abs_correlation(contribution(*best_named->c), generic_fit()) < o.other_structure_corr;
      if (lead && lead != best_named && lead->d > lead->thr && lead->d >= o.name_ratio * g_best_d) {
        lead_explains = true;
        best_named = lead;
      }
    }
    if (lead && !lead_explains && have_generic && lead->d < o.name_ratio * g_best_d &&
        o.combinations > 1) {
      std::vector<const Score*> combo{lead};
      double d_combo = lead->d, cost_combo = cost(lead->c->term);
      // Partners: among the 40 largest candidates, parts of the structure
      // the smooth function explains (in_structure), each significant and
      // above the partner floor in what it adds.
      auto may_join = [&](const Score& s, const std::vector<const Score*>& members) {
        return std::find(members.begin(), members.end(), &s) == members.end() && in_structure(s);
      };
      const std::size_t shortlist = std::min<std::size_t>(scores.size(), 40);
      // The pool of partners: the shortlist, and a drift of the structure at
      // every time constant of its grid (its scan chose the time constant
      // that fits the residual alone; beside the others another may fit).
      std::vector<const Score*> pool;
      for (std::size_t i = 0; i < shortlist; ++i) {
        const Score& sc = scores[i];
        pool.push_back(&sc);
        if (sc.c->term.kind != TermKind::thermal_drift || !in_structure(sc)) continue;
        for (const ScanFamily& f : cs.scanned) {
          const Term& base = f.base;
          if (base.kind != TermKind::thermal_drift || base.axis != sc.c->term.axis ||
              base.direction != sc.c->term.direction || base.with_axis != sc.c->term.with_axis)
            continue;
          for (double tau : f.grid) {
            if (tau == sc.c->term.tau_s) continue;
            Term t = sc.c->term;
            t.tau_s = tau;
            Cached c{t, term_columns(pb, t), Mat(), Mat(), {}};
            c.CtC = c.C.transpose() * c.C;
            c.QtC = Q.transpose() * c.C;
            rescanned.push_back(std::move(c));
            Score alt{&rescanned.back(),
                      delta_rss(rescanned.back().C, rescanned.back().CtC, rescanned.back().QtC, r),
                      0.0};
            rescanned_scores.push_back(alt);
            pool.push_back(&rescanned_scores.back());
          }
        }
      }
      Eigen::Index k_combo = lead->c->C.cols();
      for (int m = 1; m < o.combinations; ++m) {
        const Score* add = nullptr;
        double d_add = d_combo, ic_add = 0.0;
        Eigen::Index k_add = 0;
        for (const Score* sp : pool) {
          const Score& s = *sp;
          if (!may_join(s, combo)) continue;
          // One time constant per drift family in a combination.
          bool same_family = false;
          for (const Score* mb : combo)
            same_family = same_family || (mb->c->term.kind == TermKind::thermal_drift &&
                                          s.c->term.kind == TermKind::thermal_drift &&
                                          mb->c->term.axis == s.c->term.axis &&
                                          mb->c->term.direction == s.c->term.direction &&
                                          mb->c->term.with_axis == s.c->term.with_axis);
          if (same_family) continue;
          std::vector<const Score*> with = combo;
          with.push_back(&s);
          const double dj = together(with);
          // What it adds must pass its χ² and `partner_floor_share` of the
          // practical floor, in units of the residual variance the
          // combination leaves (not what the candidate alone leaves: that
          // still holds the structure the others explain).
          const Eigen::Index kj = k_combo + s.c->C.cols();
          const double s2j =
              std::max(rr - dj, 1e-300) / std::max(dof_base - static_cast<double>(kj), 1.0);
          const double thr_added =
              s2j * std::max(chi2_upper_quantile(s.c->term.columns(), o.alpha / tests_named),
                             o.partner_floor_share * lambda);
          // The partner that adds most on the criterion (a searched cycle
          // that fits a line as well as a one-column squareness costs more).
          const double ic = ic_gain(dj - d_combo, cost(s.c->term));
          if (dj - d_combo > thr_added && (!add || ic > ic_add)) {
            k_add = kj;
            add = &s;
            d_add = dj;
            ic_add = ic;
          }
        }
        if (!add) break;
        combo.push_back(add);
        k_combo = k_add;
        d_combo = d_add;
        cost_combo += cost(add->c->term);
      }
      if (combo.size() > 1 && d_combo >= o.name_ratio * g_best_d &&
          ic_gain(d_combo, cost_combo) >= ic_gain(g_best_d, g_best.columns())) {
        combination_wins = true;
        best_named = lead;
        partners.assign(combo.begin() + 1, combo.end());
        d_partners = d_combo;
        std::string names;
        for (const Score* c : combo) names += (names.empty() ? "" : " + ") + c->c->term.label();
        res.log.push_back(fmt::format(
            "step {}: {} (ΔRSS {:.6g}) explain what {} explains (ΔRSS {:.6g}) at lower cost",
            step + 1, names, d_combo, g_best.label(), g_best_d));
        // A partner the data do not prefer over another candidate in its
        // place (the combination with the other removes less by no more
        // than a one-column χ² at `alpha`) is reported with it as ambiguous.
        const double swap_margin = s2_ic * chi2_upper_quantile(1, o.alpha);
        partner_rivals.resize(partners.size());
        for (std::size_t m = 1; m < combo.size(); ++m)
          for (std::size_t i = 0; i < shortlist; ++i) {
            const Score& s = scores[i];
            if (!may_join(s, combo)) continue;
            const Term& pt = combo[m]->c->term;
            if (s.c->term.kind == pt.kind && s.c->term.axis == pt.axis &&
                s.c->term.direction == pt.direction && s.c->term.with_axis == pt.with_axis)
              continue;  // the same effect (another period or time constant)
            std::vector<const Score*> swapped = combo;
            swapped[m] = &s;
            if (together(swapped) >= d_combo - swap_margin)
              partner_rivals[m - 1].push_back(s.c->term);
          }
      }
    }

    Term pick;
    Mat C;
    double d_pick = 0.0;
    std::vector<std::string> amb;
    std::string separation;
    std::vector<Term> with_pick;  // the partners of a winning combination
    std::vector<std::vector<std::string>> with_amb;
    std::vector<std::string> with_separation;
    if (best_named && (!have_generic || combination_wins || lead_explains || other_structure ||
                       best_named->d >= o.name_ratio * g_best_d)) {
      pick = best_named->c->term;
      C = best_named->c->C;
      d_pick = best_named->d;
      // Ambiguity: near-equal candidates whose fitted contributions coincide
      // and which the data do not reject against it (`rivals_by_test`).
      // Parsimony: an alternative that costs more (columns, plus the cost of
      // a period or time constant found by search) and explains no more is
      // not a rival explanation of the same structure.
      const double rival_margin = s2_ic * chi2_upper_quantile(1, o.alpha);
      auto ambiguity = [&](const Score& target, std::vector<std::string>& names) {
        const Vec fb = contribution(*target.c);
        std::vector<Term> rivals;
        for (const Score& s : scores) {
          if (&s == &target || s.d < 0.9 * target.d) continue;
          if (cost(s.c->term) > cost(target.c->term)) continue;
          if (o.rivals_by_test && target.d - s.d >= rival_margin) continue;
          if (abs_correlation(fb, contribution(*s.c)) > o.ambiguous_corr) {
            names.push_back(s.c->term.label());
            rivals.push_back(s.c->term);
          }
        }
        for (double period : target.c->aliases) {
          Term alias = target.c->term;
          alias.period_mm = period;
          names.push_back(alias.label());
        }
        return separating_measurement(target.c->term, rivals, target.c->aliases);
      };
      separation = ambiguity(*best_named, amb);
      // A combination that won against a smooth function enters whole: its
      // members explain the structure together (a partner alone may be
      // below the practical floor, e.g. the squareness part of an
      // off-centre coupling), so each is kept with it, with its own rivals.
      for (std::size_t m = 0; m < partners.size(); ++m) {
        const Score* s = partners[m];
        Mat Cn(n, C.cols() + s->c->C.cols());
        Cn << C, s->c->C;
        C = std::move(Cn);
        with_pick.push_back(s->c->term);
        with_amb.emplace_back();
        std::string sep = ambiguity(*s, with_amb.back());
        for (const Term& t : partner_rivals[m])
          if (std::find(with_amb.back().begin(), with_amb.back().end(), t.label()) ==
              with_amb.back().end())
            with_amb.back().push_back(t.label());
        if (sep.empty() && !partner_rivals[m].empty())
          sep = separating_measurement(s->c->term, partner_rivals[m], {});
        with_separation.push_back(sep);
        d_pick = d_partners;
      }
    } else if (have_generic) {
      pick = g_best;
      C = term_columns(pb, pick);
      d_pick = g_best_d;
    } else {
      res.log.push_back(
          fmt::format("step {}: no candidate above the significance floor", step + 1));
      break;
    }

    // Held-out check. A smooth function that fails it gives way to the best
    // significant named candidate (with fewer columns it may still pass).
    Mat Xn(n, X.cols() + C.cols());
    Xn << X, C;
    double cv = cross_validated_sse(pb, Xn, y, folds, o.folds);
    // A smooth function's flexibility: the degree with the least held-out SSE.
    if (pick.kind == TermKind::unexplained) {
      const int fixed_degree = pick.degree;
      for (int degree : pick.vars.size() == 1 ? o.single_degrees : o.pair_degrees) {
        if (degree == fixed_degree) continue;
        Term t = pick;
        t.degree = degree;
        const Mat Ct = term_columns(pb, t);
        if (static_cast<double>(X.cols() + Ct.cols()) > 0.5 * static_cast<double>(n)) continue;
        Mat Xt(n, X.cols() + Ct.cols());
        Xt << X, Ct;
        const double cvt = cross_validated_sse(pb, Xt, y, folds, o.folds);
        if (cvt < cv) {
          cv = cvt;
          pick = t;
          C = Ct;
          Xn = std::move(Xt);
        }
      }
      if (pick.degree != fixed_degree) {
        const Vec b = C.transpose() * r;
        Mat G = C.transpose() * C;
        if (Q.cols() > 0) {
          const Mat QtC = Q.transpose() * C;
          G.noalias() -= QtC.transpose() * QtC;
        }
        G.diagonal().array() += 1e-12 * std::max(G.trace(), 1e-300) / static_cast<double>(G.rows());
        d_pick = b.dot(G.ldlt().solve(b));
        res.log.push_back(fmt::format("step {}: {} degree {} (held-out SSE; candidates' {})",
                                      step + 1, pick.label(), pick.degree, fixed_degree));
      }
    }
    if (!(cv < cv_prev * (1.0 - 1e-6)) && pick.kind == TermKind::unexplained && best_named) {
      res.log.push_back(fmt::format("step {}: {} rejected: held-out SSE {:.6g} ≥ {:.6g}", step + 1,
                                    pick.label(), cv, cv_prev));
      pick = best_named->c->term;
      C = best_named->c->C;
      d_pick = best_named->d;
      amb.clear();
      separation.clear();
      Xn.resize(n, X.cols() + C.cols());
      Xn << X, C;
      cv = cross_validated_sse(pb, Xn, y, folds, o.folds);
    }
    if (!(cv < cv_prev * (1.0 - 1e-6))) {
      res.log.push_back(fmt::format("step {}: {} rejected: held-out SSE {:.6g} ≥ {:.6g}", step + 1,
                                    pick.label(), cv, cv_prev));
      break;
    }
    std::string picked = pick.label();
    for (const Term& t : with_pick) picked += " + " + t.label();
    res.log.push_back(fmt::format("step {}: {} ΔRSS {:.6g} (of {:.6g}), held-out SSE {:.6g}",
                                  step + 1, picked, d_pick, rr, cv));
    cv_prev = cv;
    X = std::move(Xn);
    const Eigen::Index p0 = Q.cols();
    append_orthonormal(Q, C);
    const Mat Qnew = Q.rightCols(Q.cols() - p0);
    r -= Qnew * (Qnew.transpose() * r);
    for (Cached& c : named) {
      Mat ext(Q.cols(), c.C.cols());
      ext << c.QtC, Qnew.transpose() * c.C;
      c.QtC = std::move(ext);
    }
    chosen.push_back(pick);
    ambiguous.push_back(amb);
    separations.push_back(separation);
    for (std::size_t i = 0; i < with_pick.size(); ++i) {
      chosen.push_back(with_pick[i]);
      ambiguous.push_back(with_amb[i]);
      separations.push_back(with_separation[i]);
    }
    // A chosen fixed candidate cannot be chosen again.
    named.erase(std::remove_if(named.begin(), named.end(),
                               [&](const Cached& c) {
                                 if (c.term.label() == pick.label()) return true;
                                 for (const Term& t : with_pick)
                                   if (c.term.label() == t.label()) return true;
                                 return false;
                               }),
                named.end());
  }

  // Final joint fit of every chosen term.
  res.cv_sse = cv_prev;
  res.residual = r;
  if (chosen.size() == n_datum) {
    res.sigma_um =
        std::sqrt(r.squaredNorm() / std::max<double>(static_cast<double>(n - X.cols()), 1.0));
    if (chosen.empty()) return res;
  }
  // Two stages: the named effects jointly, then the smooth (unexplained)
  // remainder on what they leave, so that the smooth functions cannot take
  // over part of a named effect's parameters.
  std::vector<Eigen::Index> start(chosen.size());
  {
    Eigen::Index col = 0;
    for (std::size_t i = 0; i < chosen.size(); ++i) {
      start[i] = col;
      col += chosen[i].columns();
    }
  }
  struct StageFit {
    std::vector<std::size_t> terms;
    Vec beta;
    Mat inv;  // (XᵀX)⁻¹
  };
  auto fit_stage = [&](bool smooth, const Vec& target, Vec& residual) {
    StageFit f;
    Eigen::Index P = 0;
    for (std::size_t i = 0; i < chosen.size(); ++i)
      if ((chosen[i].kind == TermKind::unexplained) == smooth) {
        f.terms.push_back(i);
        P += chosen[i].columns();
      }
    residual = target;
    if (P == 0) return f;
    Mat Xs(n, P);
    Eigen::Index c = 0;
    for (std::size_t i : f.terms) {
      Xs.middleCols(c, chosen[i].columns()) = X.middleCols(start[i], chosen[i].columns());
      c += chosen[i].columns();
    }
    Mat XtX = Xs.transpose() * Xs;
    XtX.diagonal().array() += 1e-12 * XtX.trace() / static_cast<double>(P);
    Eigen::LDLT<Mat> ldlt(XtX);
    f.beta = ldlt.solve(Xs.transpose() * target);
    f.inv = ldlt.solve(Mat::Identity(P, P));
    residual = target - Xs * f.beta;
    return f;
  };
  Vec r1, r2;
  const StageFit named_fit = fit_stage(false, y, r1);
  const StageFit smooth_fit = fit_stage(true, r1, r2);
  res.residual = r2;
  const double s2 = r2.squaredNorm() / std::max<double>(static_cast<double>(n - X.cols()), 1.0);
  res.sigma_um = std::sqrt(s2);
  const Vec r_datum = y - Qd * (Qd.transpose() * y);
  // SS a term removes on its own from `target` (after the datum for the named stage).
  auto alone = [&](std::size_t i, const Vec& target, bool smooth) {
    Mat C = X.middleCols(start[i], chosen[i].columns());
    if (!smooth && Qd.cols() > 0) C -= Qd * (Qd.transpose() * C);
    Mat G = C.transpose() * C;
    G.diagonal().array() += 1e-12 * std::max(G.trace(), 1e-300) / static_cast<double>(G.rows());
    const Vec b = C.transpose() * target;
    return b.dot(G.ldlt().solve(b));
  };
  for (const StageFit* f : {&named_fit, &smooth_fit}) {
    const bool smooth = f == &smooth_fit;
    Eigen::Index col = 0;
    std::vector<SelectedTerm> stage;
    std::vector<double> overlap;
    double unique_sum = 0.0;
    for (std::size_t i : f->terms) {
      SelectedTerm st;
      st.term = chosen[i];
      const auto k = static_cast<Eigen::Index>(st.term.columns());
      const Vec bt = f->beta.segment(col, k);
      const Mat Vt = f->inv.block(col, col, k, k);
      for (Eigen::Index c = 0; c < k; ++c) {
        st.term.coef.push_back(bt[c]);
        st.term.stderr_.push_back(std::sqrt(std::max(s2 * Vt(c, c), 0.0)));
      }
      // SS this term alone removes given the others of its stage: βᵀ V⁻¹ β.
      const double drop = bt.dot(Vt.ldlt().solve(bt));
      const double of = i < n_datum ? res.baseline_sse : res.datum_sse;
      st.explained_fraction = of > 0.0 ? drop / of : 0.0;
      st.unique_fraction = st.explained_fraction;
      st.ambiguous_with = ambiguous[i];
      if (!st.ambiguous_with.empty()) st.separate_by = separations[i];
      col += k;
      if (i < n_datum) {
        res.datum.push_back(std::move(st));
        continue;
      }
      unique_sum += drop;
      overlap.push_back(std::max(alone(i, smooth ? r1 : r_datum, smooth) - drop, 0.0));
      stage.push_back(std::move(st));
    }
    // What the stage's effects remove together; the part no single one
    // removes alone is shared in proportion to the overlaps.
    const double together =
        smooth ? r1.squaredNorm() - r2.squaredNorm() : r_datum.squaredNorm() - r1.squaredNorm();
    const double shared = together - unique_sum;
    double overlap_sum = 0.0;
    for (double v : overlap) overlap_sum += v;
    for (std::size_t j = 0; j < stage.size(); ++j) {
      const double part = overlap_sum > 0.0 ? shared * overlap[j] / overlap_sum
                                            : shared / static_cast<double>(stage.size());
      stage[j].shared_fraction = res.datum_sse > 0.0 ? part / res.datum_sse : 0.0;
      stage[j].explained_fraction = stage[j].unique_fraction + stage[j].shared_fraction;
      res.explained_together += stage[j].explained_fraction;
      res.terms.push_back(std::move(stage[j]));
    }
  }
  std::stable_sort(res.terms.begin(), res.terms.end(),
                   [](const SelectedTerm& a, const SelectedTerm& b) {
                     return a.explained_fraction > b.explained_fraction;
                   });
  return res;
}

}  // namespace abbe::diagnose
