#include "structure.hpp"

#include <fmt/format.h>

#include <algorithm>

#include "abbe/diagnose/statistics.hpp"
#include "span.hpp"

namespace abbe::diagnose::selection {

void explain_structure(const Step& st, const Score* best_named, int step, StructureChoice& out,
                       std::vector<std::string>& log) {
  if (st.have_generic && (!best_named || best_named->d < st.o.name_ratio * st.g_best_d)) {
    for (const Score& sc : st.scores)
      if (sc.d > sc.thr && st.in_structure(sc)) {
        out.lead = &sc;
        break;
      }
    if (!out.lead && st.o.lead_below_floor)
      for (const Score& sc : st.scores)
        if (st.in_structure(sc)) {
          if (st.significant(sc)) out.lead = &sc;
          break;
        }
    if (out.lead && out.lead != best_named && out.lead->d > out.lead->thr &&
        out.lead->d >= st.o.name_ratio * st.g_best_d) {
      out.lead_explains = true;
    }
  }
  if (out.lead && !out.lead_explains && st.have_generic &&
      out.lead->d < st.o.name_ratio * st.g_best_d && st.o.combinations > 1) {
    // Partners: among the 40 largest candidates, parts of the structure
    // the smooth function explains (in_structure), each significant and
    // above the partner floor in what it adds.
    auto may_join = [&](const Score& s, const std::vector<const Score*>& members) {
      return std::find(members.begin(), members.end(), &s) == members.end() && st.in_structure(s);
    };
    const std::size_t shortlist = std::min<std::size_t>(st.scores.size(), 40);
    // The pool of partners: the shortlist, and a drift of the structure at
    // every time constant of its grid (its scan chose the time constant
    // that fits the residual alone; beside the others another may fit).
    std::vector<const Score*> pool;
    for (std::size_t i = 0; i < shortlist; ++i) {
      const Score& sc = st.scores[i];
      pool.push_back(&sc);
      if (sc.c->term.kind != TermKind::thermal_drift || !st.in_structure(sc)) continue;
      for (const ScanFamily& f : st.cs.scanned) {
        const Term& base = f.base;
        if (base.kind != TermKind::thermal_drift || base.axis != sc.c->term.axis ||
            base.direction != sc.c->term.direction || base.with_axis != sc.c->term.with_axis)
          continue;
        for (double tau : f.grid) {
          if (tau == sc.c->term.tau_s) continue;
          Term t = sc.c->term;
          t.tau_s = tau;
          Cached c{t, term_columns(st.pb, t), Mat(), Mat(), {}};
          c.CtC = c.C.transpose() * c.C;
          c.QtC = st.Q.transpose() * c.C;
          out.rescanned.push_back(std::move(c));
          Score alt{&out.rescanned.back(),
                    delta_rss(out.rescanned.back().C, out.rescanned.back().CtC,
                              out.rescanned.back().QtC, st.r),
                    0.0};
          out.rescanned_scores.push_back(alt);
          pool.push_back(&out.rescanned_scores.back());
        }
      }
    }
    // The smooth function's columns beside the selected span: a cyclic
    // partner must be significant beyond them too.
    Mat G;
    if (st.o.cyclic_partner_beyond_smooth) {
      G = term_columns(st.pb, st.g_best);
      if (st.Q.cols() > 0) G -= st.Q * (st.Q.transpose() * G);
    }
    auto beyond_smooth = [&](const std::vector<const Score*>& others, const Score& s) {
      Mat A(st.r.size(), 0);
      for (const Score* m : others) span::append_orthonormal(A, m->c->C - st.Q * m->c->QtC, 1e-9);
      span::append_orthonormal(A, G, 1e-9);
      const Vec rA = st.r - A * (A.transpose() * st.r);
      const Mat Cs = span::residual_of(A, s.c->C - st.Q * s.c->QtC);
      const double d = removed_by(Cs, Mat(st.r.size(), 0), rA);
      const double k_all = static_cast<double>(A.cols() + Cs.cols());
      const double s2 = std::max(rA.squaredNorm() - d, 1e-300) / std::max(st.dof_base - k_all, 1.0);
      return d > s2 * chi2_upper_quantile(s.c->term.columns(), st.o.alpha / st.tests_named);
    };
    // Greedy from one lead: the partner that adds most on the criterion,
    // up to `combinations` members.
    struct Combo {
      std::vector<const Score*> members;
      double d = 0.0, cost = 0.0;
    };
    auto grow = [&](const Score* lead) {
      Combo cb{{lead}, lead->d, st.cost(lead->c->term)};
      std::vector<const Score*>& combo = cb.members;
      double& d_combo = cb.d;
      double& cost_combo = cb.cost;
      Eigen::Index k_combo = lead->c->C.cols();
      for (int m = 1; m < st.o.combinations; ++m) {
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
          const double dj = st.together(with);
          // What it adds must pass its χ² and `partner_floor_share` of the
          // practical floor, in units of the residual variance the
          // combination leaves (not what the candidate alone leaves: that
          // still holds the structure the others explain).
          const Eigen::Index kj = k_combo + s.c->C.cols();
          const double s2j =
              std::max(st.rr - dj, 1e-300) / std::max(st.dof_base - static_cast<double>(kj), 1.0);
          const double thr_added =
              s2j * std::max(chi2_upper_quantile(s.c->term.columns(), st.o.alpha / st.tests_named),
                             st.o.partner_floor_share * st.lambda);
          // The partner that adds most on the criterion (a searched cycle
          // that fits a line as well as a one-column squareness costs more).
          const double ic = st.ic_gain(dj - d_combo, st.cost(s.c->term));
          if (dj - d_combo > thr_added && (!add || ic > ic_add) &&
              (s.c->term.kind != TermKind::cyclic || G.cols() == 0 || beyond_smooth(combo, s))) {
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
        cost_combo += st.cost(add->c->term);
      }
      return cb;
    };
    // The combination from the lead; where it does not explain the
    // structure, from the next significant parts of it (`combination_leads`;
    // not an arm offset: it carries the model's own table error): the best
    // on the criterion of those that explain the structure wins.
    auto valid = [&](const Combo& cb) {
      return cb.members.size() > 1 && cb.d >= st.o.name_ratio * st.g_best_d &&
             st.ic_gain(cb.d, cb.cost) >= st.ic_gain(st.g_best_d, st.g_best.columns());
    };
    Combo best = grow(out.lead);
    if (!valid(best)) {
      std::vector<const Score*> others;
      for (std::size_t i = 0; i < shortlist; ++i) {
        const Score& sc = st.scores[i];
        if (static_cast<int>(others.size()) + 1 >= st.o.combination_leads) break;
        if (&sc == out.lead || !st.in_structure(sc) || !st.significant(sc) ||
            sc.c->term.kind == TermKind::arm_offset)
          continue;
        others.push_back(&sc);
      }
      for (const Score* lead : others) {
        Combo cb = grow(lead);
        if (valid(cb) &&
            (!valid(best) || st.ic_gain(cb.d, cb.cost) > st.ic_gain(best.d, best.cost)))
          best = std::move(cb);
      }
    }
    if (valid(best)) out.lead = best.members.front();
    const std::vector<const Score*>& combo = best.members;
    const double d_combo = best.d;
    if (valid(best)) {
      out.combination_wins = true;
      out.partners.assign(combo.begin() + 1, combo.end());
      out.d_partners = d_combo;
      std::string names;
      for (const Score* c : combo) names += (names.empty() ? "" : " + ") + c->c->term.label();
      log.push_back(fmt::format(
          "step {}: {} (ΔRSS {:.6g}) explain what {} explains (ΔRSS {:.6g}) at lower cost",
          step + 1, names, d_combo, st.g_best.label(), st.g_best_d));
      // A partner the data do not prefer over another candidate in its
      // place (the combination with the other removes less by no more
      // than a one-column χ² at `alpha`) is reported with it as ambiguous.
      const double swap_margin = st.s2_ic * chi2_upper_quantile(1, st.o.alpha);
      out.partner_rivals.resize(out.partners.size());
      for (std::size_t m = 1; m < combo.size(); ++m)
        for (std::size_t i = 0; i < shortlist; ++i) {
          const Score& s = st.scores[i];
          if (!may_join(s, combo)) continue;
          const Term& pt = combo[m]->c->term;
          if (s.c->term.kind == pt.kind && s.c->term.axis == pt.axis &&
              s.c->term.direction == pt.direction && s.c->term.with_axis == pt.with_axis)
            continue;  // the same effect (another period or time constant)
          std::vector<const Score*> swapped = combo;
          swapped[m] = &s;
          if (st.together(swapped) >= d_combo - swap_margin)
            out.partner_rivals[m - 1].push_back(s.c->term);
        }
    }
  }
}

}  // namespace abbe::diagnose::selection
