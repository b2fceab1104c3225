#include "structure.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <set>

#include "abbe/diagnose/statistics.hpp"
#include "span.hpp"

namespace abbe::diagnose::selection {

namespace {

// Partners and leads come from the 40 largest candidates.
constexpr std::size_t kShortlist = 40;

// Not yet a member, and a part of the structure the smooth function explains.
bool may_join(const Step& st, const Score& s, const std::vector<const Score*>& members) {
  return std::find(members.begin(), members.end(), &s) == members.end() && st.in_structure(s);
}

// Two drifts of one family (axis, direction, position factor): a
// combination holds one time constant per family.
bool same_drift_family(const Term& a, const Term& b) {
  return a.kind == TermKind::thermal_drift && b.kind == TermKind::thermal_drift &&
         a.axis == b.axis && a.direction == b.direction && a.with_axis == b.with_axis;
}

// The pool of partners: the shortlist, and a drift of the structure at every
// time constant of its grid (its scan chose the time constant that fits the
// residual alone; beside the others another may fit) — where the structure
// is sought by reproduction, every drift of the shortlist, a part or not at
// its own time constant (`out.at_other_tau` then). The re-scanned drifts are
// kept in `out`.
std::vector<const Score*> partner_pool(const Step& st, std::size_t shortlist,
                                       StructureChoice& out) {
  std::vector<const Score*> pool;
  for (std::size_t i = 0; i < shortlist; ++i) {
    const Score& sc = st.scores[i];
    pool.push_back(&sc);
    // A drift not a part at its own time constant may be one at another: at
    // a short one its course is nearly done and it stands for a static term,
    // at a long one the smooth function may reproduce it. Each time constant
    // is judged as a partner (may_join).
    if (sc.c->term.kind != TermKind::thermal_drift) continue;
    const bool part = st.in_structure(sc);
    if (!part && !(st.reproduced_by && st.o.drift_parts_at_other_tau)) continue;
    for (const ScanFamily& f : st.cs.scanned) {
      if (!same_drift_family(f.base, sc.c->term)) continue;
      for (double tau : f.grid) {
        if (tau == sc.c->term.tau_s) continue;
        Term t = sc.c->term;
        t.tau_s = tau;
        out.rescanned.push_back(cached(st.pb, t, st.Q));
        const Cached& rc = out.rescanned.back();
        out.rescanned_scores.push_back(Score{&rc, delta_rss(rc.C, rc.CtC, rc.QtC, st.r), 0.0});
        pool.push_back(&out.rescanned_scores.back());
        if (!part) out.at_other_tau.insert(pool.back());
      }
    }
  }
  return pool;
}

// The smooth function's columns beside the selected span, computed when a
// cyclic partner first asks (cyclic_partner_beyond_smooth).
class SmoothSpan {
 public:
  explicit SmoothSpan(const Step& st) : st_(st) {}

  // The cycle `s` is significant in what it adds beside `others` and the
  // smooth function (χ² of its columns at alpha / tests_named).
  bool adds(const std::vector<const Score*>& others, const Score& s) {
    if (!computed_) {
      G_ = term_columns(st_.pb, st_.g_best);
      if (st_.Q.cols() > 0) G_ -= st_.Q * (st_.Q.transpose() * G_);
      computed_ = true;
    }
    if (G_.cols() == 0) return true;
    Mat A(st_.r.size(), 0);
    for (const Score* m : others) span::append_orthonormal(A, m->c->C - st_.Q * m->c->QtC, 1e-9);
    span::append_orthonormal(A, G_, 1e-9);
    const Vec rA = st_.r - A * (A.transpose() * st_.r);
    const Mat Cs = span::residual_of(A, s.c->C - st_.Q * s.c->QtC);
    const double d = removed_by(Cs, Mat(st_.r.size(), 0), rA);
    const double k_all = static_cast<double>(A.cols() + Cs.cols());
    const double s2 = std::max(rA.squaredNorm() - d, 1e-300) / std::max(st_.dof_base - k_all, 1.0);
    return d > s2 * chi2_upper_quantile(s.c->term.columns(), st_.o.alpha / st_.tests_named);
  }

 private:
  const Step& st_;
  bool computed_ = false;
  Mat G_;
};

// `t` is a linear part of a coupling among `members`: a scale or
// squareness of the coupling's direction along one of its two axes.
bool linear_part_of_coupling(const Term& t, const std::vector<const Score*>& members) {
  if (t.kind != TermKind::scale && t.kind != TermKind::squareness) return false;
  for (const Score* m : members) {
    const Term& c = m->c->term;
    if (c.kind == TermKind::coupling && c.direction == t.direction &&
        (t.axis == c.axis || t.axis == c.with_axis))
      return true;
  }
  return false;
}

// The share of the practical floor a partner must add: the whole for a
// cycle (cyclic_partner_full_floor), none for a linear part of a coupling
// in the combination (coupling_parts_at_chi2: its χ² alone), else
// partner_floor_share.
double partner_floor_share(const SelectionOptions& o, const Term& t, bool coupling_part) {
  if (t.kind == TermKind::cyclic && o.cyclic_partner_full_floor) return 1.0;
  if (coupling_part && o.coupling_parts_at_chi2) return 0.0;
  return o.partner_floor_share;
}

// What a member `t` must add beside the others of a combination that removes
// `d` with `k` columns: its χ² and partner_floor_share() of the practical
// floor, in units of the residual variance the combination leaves (not
// what the member alone leaves: that still holds the structure the others
// explain).
double partner_floor(const Step& st, const Term& t, bool coupling_part, double d, Eigen::Index k) {
  const double s2 =
      std::max(st.rr - d, 1e-300) / std::max(st.dof_base - static_cast<double>(k), 1.0);
  return s2 * std::max(chi2_upper_quantile(t.columns(), st.o.alpha / st.tests_named),
                       partner_floor_share(st.o, t, coupling_part) * st.lambda);
}

// A combination: its members (the lead first), what they remove together
// and their cost on the criterion.
struct Combo {
  std::vector<const Score*> members;
  double d = 0.0, cost = 0.0;
};

// Greedy from one lead: the partner that adds most on the criterion, up to
// `combinations` members.
Combo grow(const Step& st, const Score* lead, const std::vector<const Score*>& pool,
           SmoothSpan& smooth) {
  Combo cb{{lead}, lead->d, st.cost(lead->c->term)};
  Eigen::Index k_combo = lead->c->C.cols();
  for (int m = 1; m < st.o.combinations; ++m) {
    const Score* add = nullptr;
    double d_add = cb.d, ic_add = 0.0;
    bool part_add = false;
    Eigen::Index k_add = 0;
    for (const Score* sp : pool) {
      const Score& s = *sp;
      if (!may_join(st, s, cb.members)) continue;
      bool same_family = false;
      for (const Score* mb : cb.members)
        same_family = same_family || same_drift_family(mb->c->term, s.c->term);
      if (same_family) continue;
      std::vector<const Score*> with = cb.members;
      with.push_back(&s);
      const double dj = st.together(with);
      // What it adds must pass its floor as a partner.
      const Eigen::Index kj = k_combo + s.c->C.cols();
      const bool part = linear_part_of_coupling(s.c->term, cb.members);
      const double thr_added = partner_floor(st, s.c->term, part, dj, kj);
      // The partner that adds most on the criterion (a searched cycle that
      // fits a line as well as a one-column squareness costs more).
      const double ic = st.ic_gain(dj - cb.d, st.cost(s.c->term));
      // A linear part of a coupling in the combination comes before any
      // other partner (coupling_parts_first): with them the coupling is one
      // about any centre, and another candidate that fits a linear part
      // with more of the residual besides (an arm offset carrying the
      // model's own table error) must then add beyond it.
      const bool first = st.o.coupling_parts_first && part;
      const bool better = !add || (first != part_add ? first : ic > ic_add);
      if (dj - cb.d > thr_added && better &&
          (s.c->term.kind != TermKind::cyclic || !st.o.cyclic_partner_beyond_smooth ||
           smooth.adds(cb.members, s))) {
        k_add = kj;
        add = &s;
        d_add = dj;
        ic_add = ic;
        part_add = first;
      }
    }
    if (!add) break;
    cb.members.push_back(add);
    k_combo = k_add;
    cb.d = d_add;
    cb.cost += st.cost(add->c->term);
  }
  return cb;
}

// It explains the structure: at least `name_ratio` of the smooth function's
// ΔRSS with a criterion at least as good. With a drift that joined at
// another time constant than its own (`other_tau`, drift_parts_at_other_tau)
// its lead too must add, beside its partners, what a partner must: a lead
// chosen below the floors alone (lead_below_floor) that adds little beside
// such a drift would be named for a part of the drift.
bool explains(const Step& st, const Combo& cb, const std::set<const Score*>& other_tau) {
  if (!(cb.members.size() > 1 && cb.d >= st.o.name_ratio * st.g_best_d &&
        st.ic_gain(cb.d, cb.cost) >= st.ic_gain(st.g_best_d, st.g_best.columns())))
    return false;
  const std::vector<const Score*> partners(cb.members.begin() + 1, cb.members.end());
  if (std::none_of(partners.begin(), partners.end(),
                   [&](const Score* p) { return other_tau.count(p) > 0; }))
    return true;
  const Term& lead = cb.members.front()->c->term;
  Eigen::Index k = 0;
  for (const Score* m : cb.members) k += m->c->C.cols();
  return cb.d - st.together(partners) >
         partner_floor(st, lead, linear_part_of_coupling(lead, partners), cb.d, k);
}

// The combination from the lead; where it does not explain the structure,
// from the next significant parts of it (`combination_leads`; not an arm
// offset: it carries the model's own table error): the best on the
// criterion of those that explain the structure.
Combo best_combination(const Step& st, const Score* lead, std::size_t shortlist,
                       const std::vector<const Score*>& pool,
                       const std::set<const Score*>& other_tau) {
  SmoothSpan smooth(st);
  Combo best = grow(st, lead, pool, smooth);
  bool best_explains = explains(st, best, other_tau);
  if (best_explains) return best;
  std::vector<const Score*> others;
  for (std::size_t i = 0; i < shortlist; ++i) {
    const Score& sc = st.scores[i];
    if (static_cast<int>(others.size()) + 1 >= st.o.combination_leads) break;
    if (&sc == lead || !st.in_structure(sc) || !st.significant(sc) ||
        sc.c->term.kind == TermKind::arm_offset)
      continue;
    others.push_back(&sc);
  }
  for (const Score* other : others) {
    Combo cb = grow(st, other, pool, smooth);
    if (explains(st, cb, other_tau) &&
        (!best_explains || st.ic_gain(cb.d, cb.cost) > st.ic_gain(best.d, best.cost))) {
      best = std::move(cb);
      best_explains = true;
    }
  }
  return best;
}

// A member the data do not prefer over another candidate in its place (the
// combination with the other removes less by no more than a one-column χ²
// at `alpha`) is reported with it as ambiguous: per member, the lead first
// (lead_rivals_in_combination; else the lead's entry stays empty).
std::vector<std::vector<Term>> member_rivals(const Step& st, const Combo& combo,
                                             std::size_t shortlist) {
  const double swap_margin = st.s2_ic * chi2_upper_quantile(1, st.o.alpha);
  std::vector<std::vector<Term>> rivals(combo.members.size());
  for (std::size_t m = st.o.lead_rivals_in_combination ? 0 : 1; m < combo.members.size(); ++m)
    for (std::size_t i = 0; i < shortlist; ++i) {
      const Score& s = st.scores[i];
      if (!may_join(st, s, combo.members)) continue;
      const Term& pt = combo.members[m]->c->term;
      if (s.c->term.kind == pt.kind && s.c->term.axis == pt.axis &&
          s.c->term.direction == pt.direction && s.c->term.with_axis == pt.with_axis)
        continue;  // the same effect (another period or time constant)
      std::vector<const Score*> swapped = combo.members;
      swapped[m] = &s;
      const double d_swapped = st.together(swapped);
      if (st.o.member_rivals_by_cost && s.c->term.kind == TermKind::thermal_drift &&
          st.cost(s.c->term) > st.cost(pt) && !(d_swapped > combo.d))
        continue;  // a costlier drift and no better: the criterion's choice
      if (d_swapped >= combo.d - swap_margin) rivals[m].push_back(s.c->term);
    }
  return rivals;
}

}  // namespace

void explain_structure(const Step& st, const Score* best_named, int step, StructureChoice& out,
                       std::vector<std::string>& log) {
  if (st.have_generic && (!best_named || best_named->d < st.o.name_ratio * st.g_best_d)) {
    // A cycle leads only where it adds beside the smooth function, as a
    // cyclic partner (cyclic_partner_beyond_smooth): else it is a piece of
    // the smooth structure its searched period happened to fit.
    SmoothSpan smooth(st);
    for (const Score& sc : st.scores)
      if (sc.d > sc.thr && st.in_structure(sc)) {
        if (sc.c->term.kind == TermKind::cyclic && st.o.cyclic_partner_beyond_smooth &&
            st.o.cyclic_lead_beyond_smooth && !smooth.adds({}, sc))
          continue;
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
  if (!out.lead || out.lead_explains || !st.have_generic ||
      out.lead->d >= st.o.name_ratio * st.g_best_d || st.o.combinations <= 1)
    return;
  // Partners: among the largest candidates, parts of the structure the
  // smooth function explains (in_structure), each significant and above the
  // partner floor in what it adds.
  const std::size_t shortlist = std::min(st.scores.size(), kShortlist);
  const std::vector<const Score*> pool = partner_pool(st, shortlist, out);
  const Combo best = best_combination(st, out.lead, shortlist, pool, out.at_other_tau);
  if (!explains(st, best, out.at_other_tau)) {
    std::string names;
    for (const Score* c : best.members) names += (names.empty() ? "" : " + ") + c->c->term.label();
    log.push_back(
        fmt::format("step {}: {} (ΔRSS {:.6g}) do not explain what {} explains (ΔRSS {:.6g})",
                    step + 1, names, best.d, st.g_best.label(), st.g_best_d));
    return;
  }
  out.lead = best.members.front();
  out.combination_wins = true;
  out.partners.assign(best.members.begin() + 1, best.members.end());
  out.d_partners = best.d;
  std::string names;
  for (const Score* c : best.members) names += (names.empty() ? "" : " + ") + c->c->term.label();
  log.push_back(
      fmt::format("step {}: {} (ΔRSS {:.6g}) explain what {} explains (ΔRSS {:.6g}) at lower cost",
                  step + 1, names, best.d, st.g_best.label(), st.g_best_d));
  out.member_rivals = member_rivals(st, best, shortlist);
}

}  // namespace abbe::diagnose::selection
