#include "abbe/compensate/program_compensator.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <iterator>
#include <optional>

#include "abbe/compensate/motion_path.hpp"
#include "abbe/compensate/number_format.hpp"
#include "abbe/gcode/parser.hpp"
#include "abbe/io/input_error.hpp"
#include "abbe/path/fragmenter.hpp"

namespace abbe::compensate {
namespace {

using Eigen::Vector3d;
constexpr char kAxis[3] = {'X', 'Y', 'Z'};
constexpr char kCentre[3] = {'I', 'J', 'K'};

struct Edit {
  std::uint32_t begin = 0, end = 0;  // begin == end: insertion
  std::string text;
};

bool has_g(const gcode::Block& b, double code) {
  for (const auto& w : b.words)
    if (w.letter == 'G' && std::abs(w.value - code) < 1e-9) return true;
  return false;
}

const gcode::Word* find_word(const gcode::Block& b, char letter) {
  for (const auto& w : b.words)
    if (w.letter == letter) return &w;
  return nullptr;
}

// Rewrites one block: edits of written numbers and insertions of words.
class BlockEditor {
 public:
  BlockEditor(const gcode::Block& block, const std::string& raw, int decimals)
      : block_(block), raw_(raw), decimals_(decimals) {
    // Inserted words go right after the last axis/centre/radius word, or the last word.
    for (const auto& w : block.words) {
      if (std::string_view("XYZIJKR").find(w.letter) != std::string_view::npos) anchor_ = w.end;
      anchor_any_ = std::max(anchor_any_, w.end);
    }
    if (anchor_ == 0) anchor_ = anchor_any_;
    spaced_ = raw.find(' ') != std::string::npos || block.words.size() < 2;
  }

  // Sets the number of `letter` to `target` (program units). A written word
  // keeps its bytes when the rounded value does not change; an absent word
  // is inserted when `target` differs from `baseline` (what the block means
  // without it) at the output precision. Returns the value now in effect.
  double set(char letter, double target, double baseline, bool may_insert) {
    if (const gcode::Word* w = find_word(block_, letter)) {
      const std::string_view text(raw_.data() + w->number_begin, w->end - w->number_begin);
      const NumberStyle style = number_style(text);
      const int d = std::max(style.decimals, decimals_);
      if (round_to(target, d) == round_to(w->value, d)) return w->value;
      edits_.push_back({w->number_begin, w->end, format_number(target, style, decimals_)});
      return round_to(target, d);
    }
    if (!may_insert || round_to(target, decimals_) == round_to(baseline, decimals_))
      return baseline;
    edits_.push_back({anchor_, anchor_,
                      fmt::format("{}{}{}", spaced_ ? " " : "", letter,
                                  format_number(target, NumberStyle{}, decimals_))});
    return round_to(target, decimals_);
  }

  // Deletes a word (and the blank before it).
  void remove(char letter) {
    const gcode::Word* w = find_word(block_, letter);
    if (!w) return;
    std::uint32_t b = w->begin;
    if (b > 0 && raw_[b - 1] == ' ') --b;
    edits_.push_back({b, w->end, ""});
  }

  bool changed() const { return !edits_.empty(); }
  bool spaced() const { return spaced_; }

  std::string apply() const {
    std::vector<Edit> e = edits_;
    std::stable_sort(e.begin(), e.end(),
                     [](const Edit& a, const Edit& b) { return a.begin < b.begin; });
    std::string out;
    std::uint32_t pos = 0;
    for (const auto& x : e) {
      out.append(raw_, pos, x.begin - pos);
      out += x.text;
      pos = x.end;
    }
    out.append(raw_, pos, std::string::npos);
    return out;
  }

 private:
  const gcode::Block& block_;
  const std::string& raw_;
  int decimals_;
  std::uint32_t anchor_ = 0, anchor_any_ = 0;
  bool spaced_ = true;
  std::vector<Edit> edits_;
};

struct SolvedPoint {
  Vector3d n;             // nominal, mm
  Vector3d delta;         // c − n, mm
  double t = 0.0;         // parameter along the motion
  bool reversal = false;  // an in-plane axis of an arc reverses here: a piece ends here
};

class Compensator {
 public:
  Compensator(const std::string& file, const gcode::InterpreterConfig& config,
              const model::ErrorModel& model, const CompensateOptions& o, const TextSink& out)
      : file_(file),
        interp_(config, file),
        fragmenter_(path::FragmentOptions{o.step, 10000.0}),
        solver_(model, o.solver),
        o_(o),
        out_(out) {}

  CompensateSummary run(std::istream& in) {
    gcode::BlockReader reader(in, file_);
    gcode::Block block;
    bool first = true;
    while (reader.next(block)) {
      if (first && reader.byte_order_mark()) put("\xEF\xBB\xBF");
      first = false;
      ++s_.lines;
      ending_ = reader.line_ending();
      if (interp_.program_ended()) {
        put(reader.raw_line());
        put(ending_);
        continue;
      }
      process(block, reader.raw_line());
      if (buf_.size() > (std::size_t{1} << 20)) flush();
    }
    flush();
    return s_;
  }

 private:
  void put(std::string_view s) { buf_.append(s.data(), s.size()); }
  void flush() {
    out_(buf_.data(), buf_.size());
    buf_.clear();
  }
  void warn(std::size_t line, const std::string& text) {
    if (s_.warnings.size() < 20) s_.warnings.push_back(fmt::format("{}:{}: {}", file_, line, text));
  }

  Vector3d solve(const path::PathPoint& pp) {
    model::EvalPoint ep;
    ep.p = pp.p;
    ep.tool_length = pp.tool_length;
    ep.dir = pp.dir;
    ep.time = pp.time;
    Solution sol;
    try {
      sol = solver_.solve(ep, data_);
    } catch (const InputError& e) {
      throw InputError({file_, pp.line, 0, e.where().field, ""},
                       fmt::format("at the point ({:.4f}, {:.4f}, {:.4f}) mm: {}", pp.p.x(),
                                   pp.p.y(), pp.p.z(), e.message()));
    }
    ++s_.points;
    if (sol.out_of_range) ++s_.out_of_range_points;
    if (!sol.converged) {
      ++s_.unconverged_points;
      if (s_.unconverged_lines.size() < 20 &&
          (s_.unconverged_lines.empty() || s_.unconverged_lines.back() != pp.line))
        s_.unconverged_lines.push_back(pp.line);
    }
    const Vector3d d = sol.c - pp.p;
    s_.max_correction_um = std::max(s_.max_correction_um, 1e3 * d.norm());
    return d;
  }

  void process(const gcode::Block& block, const std::string& raw) {
    motions_.clear();
    interp_.execute(block, raw, [&](const gcode::Motion& m) {
      if (m.kind != gcode::MotionKind::dwell) motions_.push_back(m);
    });
    if (motions_.empty()) {
      if (has_g(block, 92) && 1e3 * delta_.norm() > 1e-3)
        throw InputError({file_, block.line, 1, "G92", raw},
                         "G92 at a compensated position: the offset would take up the "
                         "correction (not supported by compensate)");
      put(raw);
      put(ending_);
      return;
    }
    unit_ = interp_.inch() ? 25.4 : 1.0;
    decimals_ = o_.decimals >= 0 ? o_.decimals : (interp_.inch() ? 5 : 4);
    incremental_ = interp_.incremental();
    p_after_ = interp_.position();
    pos_after_ = interp_.program_position();
    // Fragment every motion (keeps the direction state as in predict).
    points_.assign(motions_.size(), {});
    for (std::size_t i = 0; i < motions_.size(); ++i) {
      const Vector3d start = motions_[i].start;
      fragmenter_.add(motions_[i], [&](const path::PathPoint& pp) {
        if (points_[i].empty() && pp.p == start && (pp.p - motions_[i].end).norm() > 0.0) return;
        points_[i].push_back(pp);
      });
    }
    cmd_ = prog(motions_.front().start) + delta_ / unit_;
    BlockEditor editor(block, raw, decimals_);
    std::vector<std::string> pieces;
    const bool g53 = has_g(block, 53);
    if (motions_.size() > 1)
      cycle(block, editor);
    else if (motions_[0].kind == gcode::MotionKind::rapid || g53)
      rapid(block, editor, g53);
    else
      feed(block, editor, pieces);
    if (editor.changed() || !pieces.empty()) ++s_.blocks_changed;
    put(editor.changed() ? editor.apply() : raw);
    const char* between = *ending_ ? ending_ : "\n";
    long n = block.n ? static_cast<long>(block.n->value) : 0;
    for (std::size_t k = 0; k < pieces.size(); ++k) {
      put(between);
      if (o_.renumber && block.n)
        put(fmt::format("N{}{}", n + static_cast<long>(k) + 1, editor.spaced() ? " " : ""));
      put(pieces[k]);
    }
    put(ending_);
    s_.pieces_inserted += pieces.size();
    delta_ = (cmd_ - pos_after_) * unit_;
  }

  // Program-frame coordinates (program units) of a tool-tip point of this block.
  Vector3d prog(const Vector3d& p) const { return pos_after_ + (p - p_after_) / unit_; }

  // Sets axis/centre word `letter` so that the absolute program value is
  // `target_abs`; returns the absolute value in effect. `reference` is the
  // absolute value an increment is taken from (G91).
  double set_abs(BlockEditor& ed, char letter, double target_abs, double reference,
                 double baseline_abs, bool incremental, bool may_insert) {
    if (!incremental) return ed.set(letter, target_abs, baseline_abs, may_insert);
    return reference + ed.set(letter, target_abs - reference, baseline_abs - reference, may_insert);
  }

  void rapid(const gcode::Block& block, BlockEditor& ed, bool g53) {
    if (points_[0].empty()) return;  // zero-length
    const Vector3d d = solve(points_[0].back());
    for (int a = 0; a < 3; ++a) {
      const gcode::Word* w = find_word(block, kAxis[a]);
      if (g53) {           // machine coordinates: the number moves by the correction
        if (!w) continue;  // an unwritten axis stays where it was
        const double v = ed.set(kAxis[a], w->value + d[a] / unit_, w->value, false);
        cmd_[a] = pos_after_[a] + (v - w->value);
      } else {
        const double target = prog(motions_[0].end)[a] + d[a] / unit_;
        cmd_[a] = set_abs(ed, kAxis[a], target, cmd_[a], cmd_[a], incremental_, true);
      }
    }
  }

  void cycle(const gcode::Block& block, BlockEditor& ed) {
    const auto ax = plane_axes(interp_.plane());
    const int n = ax[2];
    if (incremental_) {
      const gcode::Word* l = find_word(block, 'L');
      if (l && l->value > 1.0) {
        repeated_cycle(block, ed, static_cast<int>(std::lround(l->value)));
        return;
      }
    }
    // The hole bottom: the feed end farthest from where the cycle leaves the tool.
    std::optional<std::size_t> hole;
    double far = -1.0;
    for (std::size_t i = 0; i < motions_.size(); ++i) {
      if (motions_[i].kind != gcode::MotionKind::linear || points_[i].empty()) continue;
      const double dist = (motions_[i].end - p_after_).norm();
      if (dist > far) {
        far = dist;
        hole = i;
      }
    }
    if (!hole) return;
    const Vector3d d = solve(points_[*hole].back());
    const Vector3d h = prog(motions_[*hole].end);
    for (int k = 0; k < 2; ++k) {
      const int a = ax[static_cast<std::size_t>(k)];
      cmd_[a] = set_abs(ed, kAxis[a], h[a] + d[a] / unit_, cmd_[a], cmd_[a], incremental_, true);
    }
    if (!incremental_) {  // the depth word (absolute in G90)
      const double v = ed.set(kAxis[n], h[n] + d[n] / unit_, h[n] + depth_delta_ / unit_, true);
      depth_delta_ = (v - h[n]) * unit_;
    }
  }

  // G91 canned cycle with L repeats: one increment serves every hole, so the
  // holes get the correction δ_before + k·g (k = 1..L) with g the least-
  // squares fit to the corrections δ_k at the hole bottoms; the depth (Z
  // relative to R) moves by the mean of δ_k − δ_before along the drill axis.
  void repeated_cycle(const gcode::Block& block, BlockEditor& ed, int repeats) {
    const auto ax = plane_axes(interp_.plane());
    const int n = ax[2];
    std::vector<Vector3d> holes;  // corrections at the bottoms, in order
    for (std::size_t i = 0; i < motions_.size(); ++i) {
      if (motions_[i].kind != gcode::MotionKind::linear || points_[i].empty()) continue;
      // The feed into a hole: the drill axis moves; its end is the bottom
      // when the next motion leaves it (a retract).
      const Vector3d d = motions_[i].end - motions_[i].start;
      if (std::abs(d[n]) <= 0.0) continue;
      const bool bottom = i + 1 == motions_.size() ||
                          (motions_[i + 1].end[n] - motions_[i + 1].start[n]) * d[n] < 0.0;
      if (bottom) holes.push_back(solve(points_[i].back()));
    }
    if (holes.size() != static_cast<std::size_t>(repeats)) {
      ++s_.uncompensated_blocks;
      warn(block.line, "canned cycle with L repeats in G91: holes left uncompensated");
      return;
    }
    Vector3d num = Vector3d::Zero();
    double den = 0.0;
    double mean_n = 0.0;
    for (std::size_t k = 0; k < holes.size(); ++k) {
      const double kk = static_cast<double>(k + 1);
      num += kk * (holes[k] - delta_);
      den += kk * kk;
      mean_n += (holes[k] - delta_)[n] / static_cast<double>(holes.size());
    }
    const Vector3d g = num / den;
    for (int k = 0; k < 2; ++k) {
      const int a = ax[static_cast<std::size_t>(k)];
      const gcode::Word* w = find_word(block, kAxis[a]);
      const double inc = (w ? w->value : 0.0) + g[a] / unit_;
      const double v = ed.set(kAxis[a], inc, w ? w->value : 0.0, true);
      cmd_[a] += static_cast<double>(repeats) * (v - (w ? w->value : 0.0));
    }
    if (const gcode::Word* z = find_word(block, kAxis[n]))
      ed.set(kAxis[n], z->value + mean_n / unit_, z->value, false);
  }

  // True if a single piece from point a to point b (a line, or an arc about
  // the centre moved by the mean of the end corrections) passes within
  // tol/2 of the commanded point of every fragment point between them.
  bool piece_ok(const gcode::Motion& m, const std::vector<SolvedPoint>& sp, std::size_t a,
                std::size_t b) const {
    if (b <= a + 1) return true;
    const double tol = 0.5e-3 * o_.tol_um;
    gcode::Motion piece = m;
    piece.start = sp[a].n + sp[a].delta;
    piece.end = sp[b].n + sp[b].delta;
    if (m.kind == gcode::MotionKind::arc) {
      piece.center = m.center + 0.5 * (sp[a].delta + sp[b].delta);
      const int normal = plane_axes(m.plane)[2];
      piece.center[normal] = piece.start[normal];
      if (a != 0 || b + 1 != sp.size()) piece.rotation = m.rotation > 0 ? 1 : -1;
    }
    const MotionPath path(piece);
    for (std::size_t k = a + 1; k < b; ++k)
      if (path.distance(sp[k].n + sp[k].delta) > tol) return false;
    return true;
  }

  // The points of an arc where an in-plane axis reverses (its tangent
  // component changes sign, every quarter turn): the bidirectional tables
  // switch there, so the correction jumps and a piece must end exactly
  // there. Solved with the directions of the motion before the point.
  void add_reversals(const gcode::Motion& m, const MotionPath& path, std::vector<SolvedPoint>& sp) {
    const auto ax = plane_axes(m.plane);
    const double theta0 =
        std::atan2(m.start[ax[1]] - m.center[ax[1]], m.start[ax[0]] - m.center[ax[0]]);
    const double sweep = path.sweep();
    if (sweep == 0.0) return;
    const double half_pi = 0.5 * M_PI;
    const double k0 = std::ceil(std::min(theta0, theta0 + sweep) / half_pi);
    const double k1 = std::floor(std::max(theta0, theta0 + sweep) / half_pi);
    for (double k = k0; k <= k1; k += 1.0) {
      const double t = (k * half_pi - theta0) / sweep;
      if (t <= 1e-6 || t >= 1.0 - 1e-6) continue;
      auto it = std::lower_bound(sp.begin(), sp.end(), t,
                                 [](const SolvedPoint& x, double v) { return x.t < v; });
      // A reversal within 0.1 mm of a sample is put on the sample: a piece
      // shorter than the corrections could reverse (a full circle).
      const double near = 0.1 / std::max(path.length(), 1e-9);
      if (it != sp.end() && it != sp.begin() && std::prev(it)->t > t - near &&
          (it->t - t > t - std::prev(it)->t))
        --it;
      const bool existing = it != sp.end() && std::abs(it->t - t) < near;
      if (existing && (it == sp.begin() || std::next(it) == sp.end())) continue;
      path::PathPoint pp;
      pp.p = path.at(t);
      pp.tool_length = m.tool_length;
      pp.line = m.line;
      pp.kind = m.kind;
      // Directions just before the point: the normal axis as along the
      // whole arc, the in-plane axes from the tangent.
      pp.dir = points_[0].front().dir;
      const Vector3d v = path.at(t) - path.at(std::max(0.0, t - 1e-4));
      for (int i = 0; i < 2; ++i) {
        const int a = ax[static_cast<std::size_t>(i)];
        if (std::abs(v[a]) > 1e-9) pp.dir[static_cast<std::size_t>(a)] = v[a] > 0 ? 1 : -1;
      }
      const Vector3d d = solve(pp);
      // Only a jump of the correction (different tables on either side)
      // needs a piece end here.
      path::PathPoint after = pp;
      const Vector3d v2 = path.at(std::min(1.0, t + 1e-4)) - path.at(t);
      for (int i = 0; i < 2; ++i) {
        const int a = ax[static_cast<std::size_t>(i)];
        if (std::abs(v2[a]) > 1e-9) after.dir[static_cast<std::size_t>(a)] = v2[a] > 0 ? 1 : -1;
      }
      if (after.dir == pp.dir) continue;
      model::EvalPoint ea;
      ea.p = after.p;
      ea.tool_length = after.tool_length;
      ea.dir = after.dir;
      const Vector3d d2 = solver_.solve(ea, data_).c - after.p;
      if ((d2 - d).norm() <= 0.5e-3 * o_.tol_um) continue;
      if (existing)
        it->reversal = true;
      else
        sp.insert(it, SolvedPoint{pp.p, d, t, true});
    }
  }

  void feed(const gcode::Block& block, BlockEditor& ed, std::vector<std::string>& pieces) {
    const gcode::Motion& m = motions_[0];
    const auto& pts = points_[0];
    if (pts.empty()) return;  // zero-length: the commanded point does not move
    const MotionPath path(m);
    std::vector<SolvedPoint> sp;
    sp.reserve(pts.size() + 1);
    sp.push_back({m.start, delta_, 0.0});
    const double len = path.length();
    for (std::size_t k = 0; k < pts.size(); ++k) {
      double t = static_cast<double>(k + 1) / static_cast<double>(pts.size());
      if (!path.is_arc() && len > 0.0) t = (pts[k].p - m.start).norm() / len;
      sp.push_back({pts[k].p, solve(pts[k]), t});
    }
    if (m.kind == gcode::MotionKind::arc) add_reversals(m, path, sp);
    // Greedy pieces: each as long as the correction stays linear along it.
    std::vector<std::size_t> breaks;
    bool reversal = false;
    for (const auto& x : sp) reversal = reversal || x.reversal;
    if (!reversal && piece_ok(m, sp, 0, sp.size() - 1)) breaks.push_back(sp.size() - 1);
    // Otherwise greedy pieces, each as long as it stays within tol/2.
    for (std::size_t a = 0; breaks.empty() || breaks.back() + 1 < sp.size();) {
      std::size_t b = a + 1;
      while (b + 1 < sp.size() && !sp[b].reversal && piece_ok(m, sp, a, b + 1)) ++b;
      breaks.push_back(b);
      a = b;
    }
    const bool arc = m.kind == gcode::MotionKind::arc;
    const bool r_form = arc && find_word(block, 'R') != nullptr;
    // A multi-turn arc in pieces: every piece is at most a quarter turn
    // (pieces end at the reversal points), so the P word (turns) goes.
    if (arc && breaks.size() > 1 && std::abs(m.rotation) > 1) {
      ed.remove('P');
      ++s_.arcs_split_turns;
    }
    const auto ax = plane_axes(m.plane);
    const Vector3d centre = prog(m.center);
    std::size_t a = 0;
    for (std::size_t j = 0; j < breaks.size(); ++j) {
      const std::size_t b = breaks[j];
      const bool last = b + 1 == sp.size();
      const Vector3d target = prog(sp[b].n) + sp[b].delta / unit_;
      const Vector3d start_cmd = cmd_;
      if (j == 0) {
        for (int k = 0; k < 3; ++k) {
          const gcode::Word* w = find_word(block, kAxis[k]);
          double t = target[k];
          if (last && w && !incremental_) t = w->value + sp[b].delta[k] / unit_;
          cmd_[k] = set_abs(ed, kAxis[k], t, cmd_[k], cmd_[k], incremental_, true);
        }
        if (arc) arc_words(ed, block, m, ax, centre, sp[a], sp[b], start_cmd, r_form, nullptr);
      } else {
        std::string line;
        const char* sep = ed.spaced() ? " " : "";
        for (int k = 0; k < 3; ++k) {
          const double v = incremental_ ? round_to(target[k] - cmd_[k], decimals_)
                                        : round_to(target[k], decimals_);
          const bool write = incremental_ ? v != 0.0 : v != round_to(cmd_[k], decimals_);
          if (arc && !write && k != ax[2]) {
            // an arc piece names its in-plane end point
          } else if (!write) {
            continue;
          }
          line += fmt::format("{}{}{}", line.empty() ? "" : sep, kAxis[k],
                              format_number(v, NumberStyle{}, decimals_));
          cmd_[k] = incremental_ ? cmd_[k] + v : v;
        }
        if (arc) arc_words(ed, block, m, ax, centre, sp[a], sp[b], start_cmd, r_form, &line);
        pieces.push_back(line);
      }
      a = b;
    }
  }

  // Centre words (IJK or R) of an arc piece from sp_a to sp_b: the centre
  // moves by the mean of the two end corrections; `line` null: edit the
  // block's own words, else append to an inserted piece.
  void arc_words(BlockEditor& ed, const gcode::Block& block, const gcode::Motion& m,
                 const std::array<int, 3>& ax, const Vector3d& centre, const SolvedPoint& pa,
                 const SolvedPoint& pb, const Vector3d& start_cmd, bool r_form, std::string* line) {
    const Vector3d c = centre + 0.5 * (pa.delta + pb.delta) / unit_;
    const char* sep = ed.spaced() ? " " : "";
    if (r_form) {
      const int u = ax[0], v = ax[1];
      const double r = 0.5 * (std::hypot(start_cmd[u] - c[u], start_cmd[v] - c[v]) +
                              std::hypot(cmd_[u] - c[u], cmd_[v] - c[v]));
      const MotionPath full(m);
      const double piece_sweep = std::abs(full.sweep()) * (pb.t - pa.t);
      const double rv = piece_sweep > M_PI ? -r : r;
      if (!line) {
        const gcode::Word* w = find_word(block, 'R');
        ed.set('R', rv, w->value, false);
      } else {
        *line += fmt::format("{}R{}", sep, format_number(rv, NumberStyle{}, decimals_));
      }
      return;
    }
    const bool absolute = interp_.arc_centre_absolute();
    for (int k = 0; k < 2; ++k) {
      const int i = ax[static_cast<std::size_t>(k)];
      const double value = absolute ? c[i] : c[i] - start_cmd[i];
      if (!line) {
        ed.set(kCentre[i], value, 0.0, true);
      } else {
        *line +=
            fmt::format("{}{}{}", sep, kCentre[i], format_number(value, NumberStyle{}, decimals_));
      }
    }
  }

  std::string file_;
  gcode::Interpreter interp_;
  path::Fragmenter fragmenter_;
  PointSolver solver_;
  model::ModelData data_;
  const CompensateOptions& o_;
  const TextSink& out_;
  CompensateSummary s_;
  std::string buf_;
  const char* ending_ = "\n";

  std::vector<gcode::Motion> motions_;
  std::vector<std::vector<path::PathPoint>> points_;
  Vector3d delta_ = Vector3d::Zero();  // commanded − nominal tool tip, mm
  double depth_delta_ = 0.0;           // correction in the modal canned-cycle depth, mm
  Vector3d cmd_ = Vector3d::Zero();    // commanded point, program frame and units
  Vector3d pos_after_ = Vector3d::Zero(), p_after_ = Vector3d::Zero();
  double unit_ = 1.0;
  int decimals_ = 4;
  bool incremental_ = false;
};

}  // namespace

CompensateSummary compensate_program(std::istream& in, const std::string& file,
                                     const gcode::InterpreterConfig& config,
                                     const model::ErrorModel& model,
                                     const CompensateOptions& options, const TextSink& out) {
  Compensator c(file, config, model, options, out);
  return c.run(in);
}

}  // namespace abbe::compensate
