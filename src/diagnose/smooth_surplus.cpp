#include "smooth_surplus.hpp"

#include <fmt/format.h>

#include <algorithm>

namespace abbe::diagnose::selection {

namespace {
// Named candidates tried beside the lead (by ΔRSS, above their floors).
constexpr std::size_t kSurplusCandidates = 5;
}  // namespace

const Score* part_by_surplus(const Step& st, const Score* lead, const Mat& Cs,
                             const std::function<double(int, double)>& smooth_floor, int step,
                             std::vector<std::string>& log) {
  std::vector<const Score*> tried;
  if (lead && lead->d > lead->thr) tried.push_back(lead);
  std::size_t looked = 0;
  for (const Score& sc : st.scores) {
    if (looked >= kSurplusCandidates) break;
    if (!(sc.d > sc.thr)) continue;
    ++looked;
    const TermKind kind = sc.c->term.kind;
    if (&sc == lead || kind == TermKind::arm_offset || kind == TermKind::cyclic ||
        st.share_along_best(sc) < 0.5)
      continue;
    if (st.reproduces(Cs, sc)) tried.push_back(&sc);
  }
  const Score* best = nullptr;
  double best_surplus = 0.0, best_both = 0.0;
  for (const Score* p : tried) {
    Mat Cb(Cs.rows(), p->c->C.cols() + Cs.cols());
    Cb << p->c->C, Cs;
    const double both = removed_by(Cb, st.Q, st.r);
    if (!best || both - p->d < best_surplus) {
      best = p;
      best_surplus = both - p->d;
      best_both = both;
    }
  }
  if (!best) return nullptr;
  const auto k = static_cast<int>(Cs.cols());
  const double columns = static_cast<double>(best->c->C.cols() + Cs.cols());
  const double s2 = std::max(st.rr - best_both, 1e-300) / std::max(st.dof_base - columns, 1.0);
  const double floor = smooth_floor(k, s2);
  log.push_back(fmt::format("step {}: {} adds {:.6g} beside {} (ΔRSS {:.6g}); its floor {:.6g}",
                            step + 1, st.g_best.label(), best_surplus, best->c->term.label(),
                            best->d, floor));
  return best_surplus <= floor ? best : nullptr;
}

}  // namespace abbe::diagnose::selection
