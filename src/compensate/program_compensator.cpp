#include "abbe/compensate/program_compensator.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <iterator>
#include <limits>
#include <optional>

#include "abbe/compensate/motion_path.hpp"
#include "abbe/compensate/number_format.hpp"
#include "abbe/compensate/provenance.hpp"
#include "abbe/gcode/motion_limits.hpp"
#include "abbe/gcode/parser.hpp"
#include "abbe/io/input_error.hpp"
#include "abbe/machine/travel_check.hpp"
#include "abbe/path/fragmenter.hpp"
#include "abbe/pipeline/program_path.hpp"
#include "block_editor.hpp"
#include "cycle_corrector.hpp"
#include "piece_splitter.hpp"

namespace abbe::compensate {
namespace {

using detail::append_word;
using detail::BlockEditor;
using detail::CycleBlock;
using detail::CycleCorrector;
using detail::find_word;
using detail::merge_short_pieces;
using detail::SolvedPoint;
using detail::split_into_pieces;
using Eigen::Vector3d;
constexpr char kAxis[3] = {'X', 'Y', 'Z'};
constexpr char kCentre[3] = {'I', 'J', 'K'};

// Whether the block's text writes its arc motion code (G2/G3) itself: an arc
// block that relies on the modal code needs it written when a G1 line is
// inserted before it. (Modes come from the interpreter; this is about text.)
bool writes_arc_code(const gcode::Block& b) {
  for (const auto& w : b.words)
    if (w.letter == 'G' && (std::abs(w.value - 2.0) < 1e-9 || std::abs(w.value - 3.0) < 1e-9))
      return true;
  return false;
}

class Compensator final : public detail::CycleHost {
 public:
  Compensator(const std::string& file, const gcode::InterpreterConfig& config,
              const model::ErrorModel& model, const CompensateOptions& o, const TextSink& out)
      : file_(file),
        interp_(config, file),
        fragmenter_(path::FragmentOptions{o.step, 10000.0}),
        solver_(model, o.solver),
        o_(o),
        out_(out) {
    // Fanuc reads "X5" as 5 least increments (0.005 mm): every number
    // abbe writes there carries a decimal point ("X5.").
    fanuc_ = config.dialect.dialect == gcode::Dialect::fanuc;
    if (o.travel) travel_.emplace(*o.travel);
    plain_.point_always = fanuc_;
  }

  CompensateSummary run(std::istream& in) {
    gcode::BlockReader reader(in, file_);
    gcode::Block block;
    bool first = true;
    // The provenance block goes first, after a "%" line (and, in a Fanuc
    // program, after its O number line).
    bool header_pending = o_.provenance.has_value();
    while (reader.next(block)) {
      if (first && reader.byte_order_mark()) put("\xEF\xBB\xBF");
      first = false;
      ++s_.lines;
      ending_ = reader.line_ending();
      const std::string_view raw_line = reader.line_text();
      if (const auto at = raw_line.find(kProvenanceMarker); at != std::string::npos)
        throw InputError({file_, block.line, at + 1, "", std::string(raw_line)},
                         "this program was already compensated by abbe (it carries the "
                         "provenance block): compensating it again would double the "
                         "correction; compensate the original program");
      if (header_pending) {
        const std::string_view t = trimmed(raw_line);
        const bool before_header =
            s_.lines <= 2 && (t == "%" || (fanuc_ && !t.empty() && (t[0] == 'O' || t[0] == 'o')));
        if (!before_header) {
          put(format_provenance(*o_.provenance, *ending_ ? ending_ : "\n"));
          header_pending = false;
        }
      }
      if (interp_.program_ended()) {
        put(reader.raw_line());
        put(ending_);
        continue;
      }
      process(block, reader.raw_line());
      if (buf_.size() > (std::size_t{1} << 20)) flush();
    }
    if (header_pending) put(format_provenance(*o_.provenance, *ending_ ? ending_ : "\n"));
    flush();
    s_.min_segment_mm = o_.min_segment;
    if (s_.shortest_inserted_mm == std::numeric_limits<double>::infinity())
      s_.shortest_inserted_mm = 0.0;
    if (travel_) {
      s_.outside_travel_points = travel_->outside();
      s_.travel_text = travel_->text();
    }
    return s_;
  }

  static std::string_view trimmed(std::string_view s) {
    while (!s.empty() && (s.back() == ' ' || s.back() == '\t' || s.back() == '\r'))
      s.remove_suffix(1);
    while (!s.empty() && (s.front() == ' ' || s.front() == '\t')) s.remove_prefix(1);
    return s;
  }

 private:
  // A line that M98 repeats or that M99 returns from runs more than once
  // with one text: it cannot carry a correction for each pass.
  void refuse_subprogram_flow(const gcode::Block& block, const std::string& raw) {
    if (const gcode::Word* w = gcode::subprogram_flow_word(block))
      throw InputError({file_, block.line, static_cast<std::size_t>(w->begin) + 1, "", raw},
                       fmt::format("subprogram calls (M{}) are not compensated: the lines of a "
                                   "subprogram run once per call and one text cannot carry "
                                   "each pass's correction",
                                   static_cast<int>(w->value)));
  }

  void put(std::string_view s) { buf_.append(s.data(), s.size()); }
  void flush() {
    out_(buf_.data(), buf_.size());
    buf_.clear();
  }
  void warn(std::size_t line, const std::string& text) override {
    if (s_.warnings.size() < 20) s_.warnings.push_back(fmt::format("{}:{}: {}", file_, line, text));
  }

  Vector3d solve(const path::PathPoint& pp) override {
    if (travel_ && !travel_->add(pp.p, pp.tool_length, pp.line)) {
      if (!o_.allow_outside_travel)
        throw InputError(
            {file_, pp.line, 0, "", ""},
            fmt::format("the point ({:.4f}, {:.4f}, {:.4f}) mm is outside the "
                        "machine's travel: {} (--allow-outside-travel compensates "
                        "it anyway)",
                        pp.p.x(), pp.p.y(), pp.p.z(), travel_->describe(pp.p, pp.tool_length)));
    }
    Solution sol;
    try {
      sol = solver_.solve(pipeline::eval_point(pp), data_);
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

  void process(const gcode::Block& written, const std::string& raw) {
    if (fanuc_) refuse_subprogram_flow(written, raw);
    motions_.clear();
    interp_.execute(written, raw, [&](const gcode::Motion& m) {
      if (m.kind != gcode::MotionKind::dwell) motions_.push_back(m);
    });
    // What the interpreter read: the block itself, or its RS274/NGC form
    // (numbers in program units) for a program in another dialect.
    const gcode::Block& block = interp_.block_read();
    if (interp_.modal().motion_mode == gcode::gcode_id(87) && motions_.size() > 1)
      throw InputError({file_, block.line, anchor_column(block), "", raw},
                       "back boring (G87) is not compensated: the level it bores up to (K) "
                       "would stay nominal");
    // G80 (or no cycle since) ends a series of cycles: the interpreter's modal state says so.
    if (interp_.modal().motion_mode == gcode::gcode_id(80)) cycles_.end_series();
    if (!motions_.empty()) ++s_.motion_blocks;
    if (motions_.empty()) {
      if (interp_.non_modal_read() == gcode::gcode_id(92) && 1e3 * delta_.norm() > 1e-3)
        throw InputError({file_, block.line, 1, "G92", raw},
                         "G92 at a compensated position: the offset would take up the "
                         "correction (not supported by compensate)");
      put(raw);
      put(ending_);
      return;
    }
    // An axis word in absolute coordinates (G90, or G53's machine
    // coordinates) sets the axis' position: from here on abbe may write it.
    const bool g53 = interp_.non_modal_read() == gcode::gcode_id(53);
    if (!interp_.incremental() || g53)
      for (std::size_t a = 0; a < 3; ++a)
        if (find_word(block, kAxis[a])) known_[a] = true;
    unit_ = interp_.inch() ? 25.4 : 1.0;
    decimals_ = o_.decimals >= 0 ? o_.decimals : (interp_.inch() ? 5 : 4);
    incremental_ = interp_.incremental();
    p_after_ = interp_.position();
    pos_after_ = interp_.program_position();
    // Fragment every motion (keeps the direction state as in predict).
    points_.assign(motions_.size(), {});
    std::size_t block_points = 0;
    for (std::size_t i = 0; i < motions_.size(); ++i) {
      const Vector3d start = motions_[i].start;
      try {
        fragmenter_.add(motions_[i], [&](const path::PathPoint& pp) {
          last_point_dir_ = pp.dir;
          if (points_[i].empty() && pp.p == start && (pp.p - motions_[i].end).norm() > 0.0) return;
          if (++block_points > o_.max_block_points)
            throw gcode::MotionRefused(fmt::format(
                "the block's motions need more than {} path points at step {} mm (compensate "
                "holds one block in memory; a larger --step takes it)",
                o_.max_block_points, o_.step));
          points_[i].push_back(pp);
        });
      } catch (const gcode::MotionRefused& e) {
        throw InputError({file_, block.line, anchor_column(block), "", raw}, e.what());
      }
    }
    cmd_ = prog(motions_.front().start) + delta_ / unit_;
    BlockEditor editor(block, raw, decimals_, plain_);
    std::vector<std::string> pieces;
    std::string before;  // a micro move written before the block
    bool feed_block = false;
    if (motions_.size() == 1) cycles_.end_series();
    if (motions_.size() > 1) {
      const CycleBlock cycle{
          block,        motions_, points_,   interp_.plane(), interp_.retract_to_r(),
          incremental_, unit_,    decimals_, plain_,          p_after_,
          delta_};
      cycles_.correct(cycle, *this, editor, pieces, cmd_, s_);
    } else if (motions_[0].kind == gcode::MotionKind::rapid || g53)
      rapid(block, editor, g53);
    else
      feed_block = feed(block, raw, editor, pieces, before);
    if (editor.changed() || !pieces.empty() || !before.empty()) ++s_.blocks_changed;
    const char* between = *ending_ ? ending_ : "\n";
    if (!before.empty()) {
      put(before);
      put(between);
      ++s_.pieces_inserted;
      ++s_.takeup_moves;
    }
    put(editor.changed() ? editor.apply() : raw);
    // N numbers of the pieces: the block's + 1, 2, ...; an N beyond what a
    // double holds exactly (2^53) cannot be counted on.
    constexpr double kMaxN = 9007199254740992.0;
    if (o_.renumber && block.n && !pieces.empty() &&
        !(block.n->value + static_cast<double>(pieces.size()) < kMaxN))
      throw InputError({file_, block.line, static_cast<std::size_t>(block.n->begin) + 1, "", raw},
                       fmt::format("N{:.0f} is too large to number the {} inserted pieces after it "
                                   "(--renumber counts up to 2^53)",
                                   block.n->value, pieces.size()));
    const std::int64_t n = block.n ? static_cast<std::int64_t>(block.n->value) : 0;
    for (std::size_t k = 0; k < pieces.size(); ++k) {
      put(between);
      if (o_.renumber && block.n)
        put(fmt::format("N{}{}", n + static_cast<std::int64_t>(k) + 1, editor.spaced() ? " " : ""));
      put(pieces[k]);
    }
    put(ending_);
    s_.pieces_inserted += pieces.size();
    delta_ = (cmd_ - pos_after_) * unit_;
    if (!feed_block) last_dir_.reset();
    if (find_word(block, 'F')) feed_set_ = true;
  }

  // Column of the first axis, centre or radius word (1-based; 0: none).
  static std::size_t anchor_column(const gcode::Block& b) {
    for (const auto& w : b.words)
      if (std::string_view("XYZIJKR").find(w.letter) != std::string_view::npos)
        return static_cast<std::size_t>(w.begin) + 1;
    return b.words.empty() ? 0 : static_cast<std::size_t>(b.words.front().begin) + 1;
  }

  // Program-frame coordinates (program units) of a tool-tip point of this block.
  Vector3d prog(const Vector3d& p) const override { return pos_after_ + (p - p_after_) / unit_; }

  // Sets axis/centre word `letter` so that the absolute program value is
  // `target_abs`; returns the absolute value in effect. `reference` is the
  // absolute value an increment is taken from (G91).
  double set_abs(BlockEditor& ed, char letter, double target_abs, double reference,
                 double baseline_abs, bool incremental, bool may_insert) override {
    // No word for an axis whose position the program has not yet set.
    const int axis = letter - 'X';
    if (axis >= 0 && axis < 3 && !known_[static_cast<std::size_t>(axis)]) may_insert = false;
    if (!incremental) return ed.set(letter, target_abs, baseline_abs, may_insert);
    return reference + ed.set(letter, target_abs - reference, baseline_abs - reference, may_insert);
  }

  // A motion that does not move: its axis words name the point's commanded
  // position — the correction there with the directions the machine has
  // (those of the last motion): where the tool already is after a feed or a
  // rapid; after a canned cycle (whose clearance moves keep their nominal
  // height) the corrected point, a move of a few µm (written and changed
  // axes, as for a rapid).
  void hold(BlockEditor& ed) {
    const gcode::Motion& m = motions_[0];
    const Vector3d target = prog(m.end) + solve_at(m, m.end, last_point_dir_) / unit_;
    for (int k = 0; k < 3; ++k)
      cmd_[k] = set_abs(ed, kAxis[k], target[k], cmd_[k], cmd_[k], incremental_, true);
  }

  void rapid(const gcode::Block& block, BlockEditor& ed, bool g53) {
    if (points_[0].empty()) {  // zero-length
      if (!g53) hold(ed);
      return;
    }
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

  // `takeup`: a take-up (micro) move; short pieces are counted by
  // merge_short_pieces as kept pieces, not here.
  void note_inserted_length(double mm, bool takeup) {
    s_.shortest_inserted_mm = std::min(s_.shortest_inserted_mm, mm);
    if (takeup && mm < o_.min_segment) ++s_.short_takeup_moves;
  }

  // A reversal jump (mm) taken up along the move rather than by a micro
  // move: below the minimum segment, and within tol unless spreading is
  // asked for whatever the jump.
  bool spreads(double jump) const {
    return jump < o_.min_segment && (o_.spread_takeups || 1e3 * jump <= o_.tol_um);
  }

  void note_takeup(const Vector3d& jump) {
    ++s_.takeups_spread;
    s_.max_takeup_um = std::max(s_.max_takeup_um, 1e3 * jump.norm());
  }

  Vector3d solve_at(const gcode::Motion& m, const Vector3d& p,
                    const std::array<std::int8_t, 3>& dir) {
    path::PathPoint pp;
    pp.p = p;
    pp.tool_length = m.tool_length;
    pp.line = m.line;
    pp.kind = m.kind;
    pp.dir = dir;
    return solve(pp);
  }

  // A feed move: solved fragment points, then the longest pieces that stay
  // within tol/2. Returns true (a feed block).
  bool feed(const gcode::Block& block, const std::string& raw, BlockEditor& ed,
            std::vector<std::string>& pieces, std::string& before) {
    const gcode::Motion& m = motions_[0];
    auto& pts = points_[0];
    if (pts.empty()) {  // zero-length: the commanded point does not move
      hold(ed);
      return false;
    }
    const bool arc = m.kind == gcode::MotionKind::arc;
    const MotionPath path(m);
    const double len = path.length();
    const double near = len > 0.0 ? kNearReversal / len : 1.0;
    // Reversal points of an arc (an in-plane axis changes direction): the
    // tables switch there. Those within kNearReversal of an end count as at
    // that end: directions are taken at t clamped into [lo, hi].
    const double lo = path.near_lo(kNearReversal), hi = path.near_hi(kNearReversal);
    auto& reversals = reversals_;
    reversals.clear();
    if (arc) path.for_each_reversal(lo, hi, [&](double t) { reversals.push_back(t); });
    const auto dir0 = pts.front().dir;
    if (arc) {
      for (std::size_t k = 0; k < pts.size(); ++k) {
        const double t = static_cast<double>(k + 1) / static_cast<double>(pts.size());
        if (t < lo || t > hi) pts[k].dir = path.directions(dir0, std::clamp(t, lo, hi));
      }
    }
    // The start: solved with this motion's directions; a jump from the
    // correction the previous motion ended with (an axis reverses at the
    // corner) is taken by a micro move before the block.
    const std::array<std::int8_t, 3> start_dir = path.directions(dir0, lo);
    Vector3d d_start = delta_;
    if (!(last_dir_ && *last_dir_ == start_dir && last_end_ == m.start))
      d_start = solve_at(m, m.start, start_dir);
    bool micro_start = 1e3 * (d_start - delta_).norm() > 0.25 * o_.tol_um;
    // A jump shorter than the minimum segment is taken up over the first
    // min_segment + |jump| of the move instead of by a micro move of its
    // own (docs/compensation.md, "Segment length").
    // A reversal jump shorter than the minimum segment is not given a micro
    // move: the piece that starts at the reversal takes it up, and ends at
    // the take-up point min_segment + 2|jump| further on (commanded length
    // ≥ min_segment), or at the next forced end or the end of the move when
    // those come first. `takeup_t`: the pending take-up point; `spread_from`:
    // where the jump being taken up was (the next point pushed ends it).
    std::optional<double> takeup_t, spread_from;
    const double l_min = o_.min_segment;
    auto takeup_at = [&](double t_from, double jump, double next) -> std::optional<double> {
      const double t_u = t_from + (l_min + 2.0 * jump + 1e-7) / len;
      if (t_u < next - near && t_u < 1.0 - near) return t_u;
      return std::nullopt;
    };
    if (micro_start && spreads((d_start - delta_).norm())) {
      const double jump = (d_start - delta_).norm();
      takeup_t = takeup_at(0.0, jump, reversals.empty() ? hi : reversals.front());
      spread_from = 0.0;
      note_takeup(d_start - delta_);
      micro_start = false;
    }
    if (!micro_start) d_start = delta_;
    auto& sp = sp_;  // reused: no allocation per block
    sp.clear();
    sp.push_back({m.start, d_start, 0.0, false, d_start, false});
    std::size_t r = 0;
    const double jump_tol = 0.25e-3 * o_.tol_um;
    // Pushes a solved point; the first after a spread jump is a forced end.
    auto push = [&](const SolvedPoint& x) {
      sp.push_back(x);
      if (spread_from && x.t > *spread_from) {
        sp.back().reversal = true;
        s_.max_takeup_length_mm = std::max(s_.max_takeup_length_mm, (x.t - *spread_from) * len);
        spread_from.reset();
      }
    };
    // The take-up point, solved with the directions there.
    auto push_takeup = [&](double tb) {
      const Vector3d nb = path.at(tb);
      const Vector3d db = solve_at(m, nb, path.directions(dir0, std::clamp(tb, lo, hi)));
      while (sp.size() > 1 && sp.back().t > tb - near && !sp.back().reversal) sp.pop_back();
      push({nb, db, tb, true, db, false});
      takeup_t.reset();
    };
    for (std::size_t k = 0; k < pts.size(); ++k) {
      double t = static_cast<double>(k + 1) / static_cast<double>(pts.size());
      if (!arc && len > 0.0) t = (pts[k].p - m.start).norm() / len;
      const bool last = k + 1 == pts.size();
      if (takeup_t && *takeup_t <= t) push_takeup(*takeup_t);
      // Reversals before this point: a piece ends exactly there.
      while (r < reversals.size() && reversals[r] <= t + near && (!last || reversals[r] < t)) {
        const double tr = reversals[r++];
        const Vector3d nr = path.at(tr);
        const Vector3d d_before = solve_at(m, nr, path.directions(dir0, tr));
        const Vector3d d_after = solve_at(m, nr, path.directions(dir0, std::min(hi, tr + 1e-6)));
        const double jump = (d_after - d_before).norm();
        if (jump <= jump_tol) continue;
        // No fragment point closer than kNearReversal before it.
        while (sp.size() > 1 && sp.back().t > tr - near && !sp.back().reversal) sp.pop_back();
        if (spreads(jump)) {
          push({nr, d_before, tr, true, d_before, false});
          note_takeup(d_after - d_before);
          takeup_t = takeup_at(tr, jump, r < reversals.size() ? reversals[r] : hi);
          spread_from = tr;
          if (takeup_t && *takeup_t <= t) push_takeup(*takeup_t);
        } else {
          push({nr, d_before, tr, true, d_after, true});
        }
      }
      if (!last && !sp.empty() && sp.back().reversal && t - sp.back().t < near) continue;
      const Vector3d d = solve(pts[k]);
      push({pts[k].p, d, t, false, d, false});
    }
    // The longest pieces within tol/2, ending at every forced point; then
    // no piece shorter than the minimum segment where merging keeps tol/2.
    auto& breaks = breaks_;
    split_into_pieces(m, sp, 0.5e-3 * o_.tol_um, breaks);
    s_.short_pieces_kept +=
        merge_short_pieces(m, sp, len, o_.min_segment, 0.5e-3 * o_.tol_um, breaks);
    const bool r_form = arc && find_word(block, 'R') != nullptr;
    // A multi-turn arc in pieces: every piece is at most a quarter turn
    // (pieces end at the reversal points), so the P word (turns) goes.
    if (arc && breaks.size() > 1 && std::abs(m.rotation) > 1) {
      ed.remove('P');
      ++s_.arcs_split_turns;
    }
    const auto ax = plane_axes(m.plane);
    const Vector3d centre = prog(m.center);
    const char* motion_word = m.rotation > 0 ? "G3" : "G2";
    bool block_written = false;
    if (micro_start) {
      const Vector3d target = prog(m.start) + d_start / unit_;
      if (!arc) {  // the block itself makes the micro move; the pieces follow
        for (int k = 0; k < 3; ++k)
          cmd_[k] = set_abs(ed, kAxis[k], target[k], cmd_[k], cmd_[k], incremental_, true);
        block_written = true;
        ++s_.takeup_moves;
        note_inserted_length((d_start - delta_).norm(), true);
      } else {  // a G1 line before the block, which then needs its motion word
        before = micro_line(target, ed.spaced());
        note_inserted_length((d_start - delta_).norm(), true);
        if (!before.empty() && !feed_set_) {
          if (const gcode::Word* f = find_word(block, 'F'))
            before += (ed.spaced() ? " " : "") + raw.substr(f->begin, f->end - f->begin);
        }
        if (!before.empty() && !writes_arc_code(block)) ed.insert_before_axes(motion_word);
      }
    }
    std::size_t a = 0;
    bool after_micro = false;
    for (std::size_t j = 0; j < breaks.size(); ++j) {
      const std::size_t b = breaks[j];
      const bool last = b + 1 == sp.size();
      const Vector3d target = prog(sp[b].n) + sp[b].delta / unit_;
      const Vector3d start_cmd = cmd_;
      if (j > 0 || block_written)
        note_inserted_length(arc ? (sp[b].t - sp[a].t) * len
                                 : ((sp[b].n + sp[b].delta) - (sp[a].n + sp[a].delta_out)).norm(),
                             false);
      if (j == 0 && !block_written) {
        for (int k = 0; k < 3; ++k) {
          const gcode::Word* w = find_word(block, kAxis[k]);
          double t = target[k];
          if (last && w && !incremental_) t = w->value + sp[b].delta[k] / unit_;
          cmd_[k] = set_abs(ed, kAxis[k], t, cmd_[k], cmd_[k], incremental_, true);
        }
        if (arc) arc_words(ed, block, m, ax, centre, sp[a], sp[b], start_cmd, r_form, nullptr);
      } else {
        std::string line = after_micro ? motion_word : "";
        // An arc piece names its in-plane end point.
        append_axes(line, target, ed.spaced(), arc ? (1 << ax[0]) | (1 << ax[1]) : 0);
        if (arc) arc_words(ed, block, m, ax, centre, sp[a], sp[b], start_cmd, r_form, &line);
        pieces.push_back(line);
      }
      after_micro = false;
      if (sp[b].micro && !last) {
        const std::string mline = micro_line(prog(sp[b].n) + sp[b].delta_out / unit_, ed.spaced());
        if (!mline.empty()) {
          ++s_.takeup_moves;
          note_inserted_length((sp[b].delta_out - sp[b].delta).norm(), true);
          pieces.push_back(mline);
          after_micro = arc;
        }
      }
      a = b;
    }
    last_dir_ = pts.back().dir;
    last_end_ = m.end;
    return true;
  }

  // Appends to `line` the axis words that take the commanded point to
  // `target` (program frame and units): the axes whose written value
  // changes and those in the bit mask `always`. Updates cmd_; returns true
  // if a word was appended.
  bool append_axes(std::string& line, const Vector3d& target, bool spaced, int always) {
    bool any = false;
    for (int k = 0; k < 3; ++k) {
      if (!known_[static_cast<std::size_t>(k)] && !(always & (1 << k))) continue;
      const double v =
          incremental_ ? round_to(target[k] - cmd_[k], decimals_) : round_to(target[k], decimals_);
      const bool write = incremental_ ? v != 0.0 : v != round_to(cmd_[k], decimals_);
      if (!write && !(always & (1 << k))) continue;
      any = true;
      append_word(line, line.empty() || !spaced ? "" : " ", kAxis[k], v, plain_, decimals_);
      cmd_[k] = incremental_ ? cmd_[k] + v : v;
    }
    return any;
  }

  // "G1 X.. Y.. Z..": a straight move of the commanded point to `target`
  // (program frame and units), only the axes whose written value changes;
  // empty if none does. Updates cmd_.
  std::string micro_line(const Vector3d& target, bool spaced) {
    std::string line = "G1";
    return append_axes(line, target, spaced, 0) ? line : std::string();
  }

  // Centre words (IJK or R) of an arc piece from sp_a to sp_b: the centre
  // moves by the mean of the two end corrections; `line` null: edit the
  // block's own words, else append to an inserted piece.
  void arc_words(BlockEditor& ed, const gcode::Block& block, const gcode::Motion& m,
                 const std::array<int, 3>& ax, const Vector3d& centre, const SolvedPoint& pa,
                 const SolvedPoint& pb, const Vector3d& start_cmd, bool r_form, std::string* line) {
    const Vector3d c = centre + 0.5 * (pa.delta_out + pb.delta) / unit_;
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
        append_word(*line, sep, 'R', rv, plain_, decimals_);
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
        append_word(*line, sep, kCentre[i], value, plain_, decimals_);
      }
    }
  }

  std::string file_;
  std::optional<machine::TravelCheck> travel_;
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
  Vector3d cmd_ = Vector3d::Zero();    // commanded point, program frame and units
  Vector3d pos_after_ = Vector3d::Zero(), p_after_ = Vector3d::Zero();
  double unit_ = 1.0;
  int decimals_ = 4;
  bool fanuc_ = false;
  NumberStyle plain_;  // of the words abbe writes anew
  bool incremental_ = false;
  // Directions with which delta_ was solved when the previous block was a
  // feed ending at last_end_ (else empty): a feed starting there with the
  // same directions needs no new solution of its start.
  std::optional<std::array<std::int8_t, 3>> last_dir_;
  bool feed_set_ = false;        // an F word was seen before the block
  std::vector<SolvedPoint> sp_;  // feed(): the solved points of the move (reused)
  std::vector<std::size_t> breaks_;
  std::vector<double> reversals_;
  std::array<std::int8_t, 3> last_point_dir_{0, 0, 0};  // of the last fragment point
  CycleCorrector cycles_;
  // Per axis: the program has set its position (an absolute axis word).
  // Before that the start is the assumed machine home: abbe writes no word
  // for the axis (docs/compensation.md, "Running it on a machine").
  std::array<bool, 3> known_{false, false, false};
  Vector3d last_end_ = Vector3d::Zero();
};

}  // namespace

std::string segment_text(const CompensateSummary& s) {
  if (s.lines == 0) return {};
  const auto per_1000 = [](std::size_t n, std::size_t of) {
    return of ? 1000.0 * static_cast<double>(n) / static_cast<double>(of) : 0.0;
  };
  const std::size_t split = s.pieces_inserted - std::min(s.pieces_inserted, s.takeup_moves);
  std::string t = fmt::format(
      "  inserted moves: {} ({:.1f} per 1000 lines, {:.1f} per 1000 motion blocks): {} pieces of "
      "split moves, {} take-up moves at reversals\n",
      s.pieces_inserted, per_1000(s.pieces_inserted, s.lines),
      per_1000(s.pieces_inserted, s.motion_blocks), split, s.takeup_moves);
  if (s.pieces_inserted || s.takeup_moves)
    t += fmt::format("  shortest inserted move {:.4f} mm (--min-segment {} mm)\n",
                     s.shortest_inserted_mm, s.min_segment_mm);
  if (s.takeups_spread)
    t += fmt::format(
        "  {} reversal jumps below --min-segment taken up along the move (largest {:.2f} µm, "
        "over at most {:.4f} mm: the path may leave the nominal by up to the jump there)\n",
        s.takeups_spread, s.max_takeup_um, s.max_takeup_length_mm);
  if (s.short_takeup_moves)
    t += fmt::format(
        "  {} moves shorter than --min-segment: take-up moves of reversal jumps beyond --tol "
        "(--spread-takeups takes them up along the move, off the path by up to the jump)\n",
        s.short_takeup_moves);
  if (s.short_pieces_kept)
    t += fmt::format("  {} pieces shorter than --min-segment kept (merging them broke --tol)\n",
                     s.short_pieces_kept);
  return t;
}

CompensateSummary compensate_program(std::istream& in, const std::string& file,
                                     const gcode::InterpreterConfig& config,
                                     const model::ErrorModel& model,
                                     const CompensateOptions& options, const TextSink& out) {
  Compensator c(file, config, model, options, out);
  return c.run(in);
}

}  // namespace abbe::compensate
