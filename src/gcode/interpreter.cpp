#include "abbe/gcode/interpreter.hpp"

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <string_view>

#include "abbe/gcode/motion_limits.hpp"
#include "abbe/io/input_error.hpp"
#include "fanuc_dialect.hpp"
#include "interpreter_steps.hpp"
#include "word_use.hpp"

namespace abbe::gcode {

namespace detail {

constexpr char kAxisLetters[6] = {'X', 'Y', 'Z', 'A', 'B', 'C'};

bool uses_axis_words(int non_modal) {
  return non_modal == gcode_id(92) || non_modal == gcode_id(10) || non_modal == gcode_id(28) ||
         non_modal == gcode_id(30) || non_modal == gcode_id(52);
}

bool is_integer(double v) { return std::abs(v - std::round(v)) < 1e-6; }

const char* plane_name(Plane plane) {
  switch (plane) {
    case Plane::xz:
      return "XZ";
    case Plane::yz:
      return "YZ";
    default:
      return "XY";
  }
}

BlockPlan plan_block(const ModalState& st, const BlockCodes& c, const BlockContext& ctx) {
  BlockPlan b{c, ctx};
  const auto& motion_code = c.group(GGroup::motion);
  const auto& non_modal = c.group(GGroup::non_modal);
  b.non_modal = non_modal ? non_modal->code : -1;
  const auto& tool_length = c.group(GGroup::tool_length);
  // G43.1 and G43.2 take the axis words as the tool offset (rs274ngc: no
  // motion; G43.2 refuses them beside an H word).
  const bool g43_1 =
      tool_length && (tool_length->code == gcode_id(43, 1) || tool_length->code == gcode_id(43, 2));
  const int axis_user = g43_1 && !uses_axis_words(b.non_modal) ? tool_length->code : b.non_modal;
  const bool g92_axes = uses_axis_words(b.non_modal) || g43_1;
  // The first axis word (X Y Z A B C), where axis-word errors point.
  const auto first_axis = [&c]() -> const Word* {
    for (char a : kAxisLetters)
      if (c.has(a)) return c.word(a);
    return nullptr;
  };

  if ((b.non_modal == gcode_id(28, 1) || b.non_modal == gcode_id(30, 1)) && c.has_axis_word())
    ctx.fail(first_axis(), fmt::format("{} takes no axis words (it stores the current position)",
                                       gcode_name(b.non_modal)));

  if (g43_1 && uses_axis_words(b.non_modal) && c.has_axis_word())
    ctx.fail(tool_length->word,
             fmt::format("cannot use two G codes that both use axis words ({} and {})",
                         gcode_name(tool_length->code), gcode_name(b.non_modal)));

  // The motion this block makes (rs274ngc: an explicit motion code, or the
  // modal one when axis words are present and nothing else uses them).
  if (motion_code) {
    b.motion = motion_code->code;
    b.motion_word = motion_code->word;
    if (g92_axes && c.has_axis_word())
      ctx.fail(b.motion_word,
               fmt::format("cannot use two G codes that both use axis words ({} and {})",
                           gcode_name(b.motion), gcode_name(axis_user)));
  } else if (c.has_axis_word() && !g92_axes) {
    if (st.motion_mode == gcode_id(80))
      ctx.fail(first_axis(), "axis words without a motion code (no motion mode is active)");
    b.motion = st.motion_mode;
    b.motion_word = first_axis();
  }
  if (b.motion == gcode_id(80) && c.has_axis_word() && !g92_axes)
    ctx.fail(first_axis(), "axis words with G80 (canned cycle cancel)");
  if (b.non_modal == gcode_id(92) && !c.has_axis_word())
    ctx.fail(non_modal->word, "G92 without axis words");
  if (b.non_modal == gcode_id(52) && !c.has_axis_word())
    ctx.fail(non_modal->word, "G52 without axis words");
  if (g92_axes && c.has_rotary_word())
    for (char a : {'A', 'B', 'C'})
      if (c.has(a))
        ctx.fail(c.word(a), fmt::format("rotary axis word {} with {} is not supported "
                                        "(3-axis machines: X, Y, Z)",
                                        a, gcode_name(axis_user)));
  // rs274ngc: polar words only with a motion.
  if (g92_axes && c.has_polar_word())
    ctx.fail(c.has('@') ? c.word('@') : c.word('^'),
             fmt::format("polar coordinates (@, ^) can only be used for motion, not with {}",
                         gcode_name(axis_user)));

  const auto& path = c.group(GGroup::path_control);
  const auto& comp = c.group(GGroup::cutter_comp);
  check_word_use(c, ctx,
                 {b.motion, b.non_modal, path ? path->code : -1,
                  tool_length ? tool_length->code : -1, comp ? comp->code : -1});
  return b;
}

bool is_plain_block(const ExecState& st, const BlockCodes& c) {
  constexpr std::uint32_t kMotionGroup = 1U << static_cast<unsigned>(GGroup::motion);
  constexpr auto bit = [](char letter) { return 1U << BlockCodes::letter_index(letter); };
  constexpr std::uint32_t kPlainLetters =
      bit('X') | bit('Y') | bit('Z') | bit('F') | bit('S') | bit('T');
  constexpr std::uint32_t kArcLetters = bit('I') | bit('J') | bit('K') | bit('R') | bit('P');
  if ((c.g_mask & ~kMotionGroup) != 0 || c.m_mask != 0 ||
      (c.letter_mask & ~(kPlainLetters | kArcLetters)) != 0 || st.comp.side != 0)
    return false;
  const CodeWord* code = c.group(GGroup::motion);
  const int motion = code ? code->code : c.has_axis_word() ? st.motion_mode : -1;
  // rs274ngc: the move just after G40 must be straight (check_comp_block).
  if (motion == gcode_id(2) || motion == gcode_id(3)) return !st.comp.exit_pending;
  return (c.letter_mask & kArcLetters) == 0 &&
         (motion == -1 || motion == gcode_id(0) || motion == gcode_id(1));
}

BlockPlan plan_plain_block(const ModalState& st, const BlockCodes& c, const BlockContext& ctx) {
  BlockPlan b{c, ctx};
  if (const CodeWord* code = c.group(GGroup::motion)) {
    b.motion = code->code;
    b.motion_word = code->word;
  } else if (c.has_axis_word()) {
    b.motion = st.motion_mode;
    for (char a : {'X', 'Y', 'Z'})
      if (!b.motion_word) b.motion_word = c.word(a);
  }
  return b;
}

// Rotary words (A, B, C) are accepted while their axis does not move: abbe
// models 3-axis machines. One warning per program; a move is refused by name.
void check_rotary_words(ExecState& st, const BlockPlan& b) {
  const BlockCodes& c = b.codes;
  if (!c.has_rotary_word()) return;
  for (int i = 0; i < 3; ++i) {
    const char letter = static_cast<char>('A' + i);
    const Word* w = c.word(letter);
    if (!w) continue;
    const double current = st.rotary[static_cast<std::size_t>(i)];
    const double target = st.incremental ? current + w->value : w->value;
    if (target != current)
      b.ctx.fail(w, fmt::format("rotary axis {} moves (from {}{} to {}{}): abbe models 3-axis "
                                "machines (X, Y, Z)",
                                letter, letter, current, letter, target));
  }
  if (!st.rotary_warned) {
    st.rotary_warned = true;
    spdlog::warn("{}:{}: rotary axis words (A, B, C) that never move are ignored (3-axis model)",
                 st.file, b.ctx.line);
  }
}

}  // namespace detail

Interpreter::Interpreter(InterpreterConfig config, std::string file)
    : state_(std::make_unique<detail::ExecState>()) {
  state_->config = std::move(config);
  state_->file = std::move(file);
  state_->work_offsets = state_->config.work_offsets;
  state_->g28_home = state_->config.g28_position;
  state_->g30_home = state_->config.g30_position;
  // Initial position is the tool tip; without G43 the program drives s = P + L·e_z.
  state_->pos = state_->config.initial_position - state_->config.work_offsets[0];
  state_->pos.z() += state_->config.default_tool_length;
}

Interpreter::~Interpreter() = default;
Interpreter::Interpreter(Interpreter&&) noexcept = default;
Interpreter& Interpreter::operator=(Interpreter&&) noexcept = default;

const ModalState& Interpreter::modal() const { return *state_; }
int Interpreter::non_modal_read() const { return state_->read_non_modal; }

const Block& Interpreter::block_read() const {
  static const Block kNone;
  return state_->read_block ? *state_->read_block : kNone;
}
bool Interpreter::program_ended() const { return state_->ended; }
std::size_t Interpreter::motions_delivered() const { return state_->delivered; }
bool Interpreter::inch() const { return state_->inch; }
bool Interpreter::incremental() const { return state_->incremental; }
bool Interpreter::arc_centre_absolute() const { return state_->arc_centre_absolute; }
Plane Interpreter::plane() const { return state_->plane; }
bool Interpreter::retract_to_r() const { return state_->retract_to_r; }
Eigen::Vector3d Interpreter::program_position() const { return state_->pos; }
Eigen::Vector3d Interpreter::position() const { return state_->tip(state_->pos); }

void Interpreter::execute(const Block& written, std::string_view raw_line, const MotionSink& sink) {
  if (written.has_code()) {
    // The first construct: the O-word, a setting's '#' or a computed word's letter.
    std::uint32_t column = written.o.keyword != OKeyword::none ? written.o.column : UINT32_MAX;
    if (!written.settings.empty()) column = std::min(column, written.settings.front().column);
    if (!written.word_expressions.empty())
      column = std::min(column, written.words[written.word_expressions.front().word].begin);
    if (column == UINT32_MAX) column = 0;
    throw InputError(SourceLocation{state_->file, written.line, std::size_t{column} + 1, "",
                                    std::string(raw_line)},
                     state_->config.dialect.dialect == Dialect::fanuc
                         ? "macro variables, expressions and O-word control flow (#, [...], "
                           "o... sub) are not supported in the Fanuc dialect"
                         : "parameters, expressions and O-words are not supported by a command "
                           "that rewrites the program line by line");
  }
  for (const Word& w : written.words) {
    if (w.letter == 'G' && (std::abs(w.value - 41.0) < 1e-6 || std::abs(w.value - 42.0) < 1e-6 ||
                            std::abs(w.value - 41.1) < 1e-6 || std::abs(w.value - 42.1) < 1e-6))
      throw InputError(SourceLocation{state_->file, written.line, std::size_t{w.begin} + 1, "",
                                      std::string(raw_line)},
                       "cutter radius compensation (G41/G42) is not supported by a command that "
                       "rewrites the program line by line");
    if (w.letter == 'G' &&
        (std::abs(w.value - 43.1) < 1e-6 ||
         (std::abs(w.value - 43.2) < 1e-6 &&
          std::any_of(written.words.begin(), written.words.end(), [](const Word& v) {
            return v.letter == 'X' || v.letter == 'Y' || v.letter == 'Z';
          }))))
      throw InputError(SourceLocation{state_->file, written.line, std::size_t{w.begin} + 1, "",
                                      std::string(raw_line)},
                       fmt::format("a dynamic tool length offset ({}) is not supported by a "
                                   "command that rewrites the program line by line (its Z word "
                                   "is not a coordinate)",
                                   std::abs(w.value - 43.1) < 1e-6 ? "G43.1" : "G43.2 Z"));
    if (w.letter == '@' || w.letter == '^')
      throw InputError(SourceLocation{state_->file, written.line, std::size_t{w.begin} + 1, "",
                                      std::string(raw_line)},
                       "polar coordinates (@, ^) are not supported by a command that rewrites "
                       "the program line by line");
  }
  execute_evaluated(written, raw_line, sink);
}

void Interpreter::finish(const MotionSink& sink) {
  detail::ExecState& st = *state_;
  if (st.comp.queue.empty()) return;
  auto deliver = [&](Motion& m) {
    ++st.delivered;
    sink(m);
  };
  st.deliver = detail::make_hook(deliver);
  detail::comp_flush(st);
  st.deliver = {};
}

void Interpreter::enter_call() { state_->save_slots.emplace_back(); }

void Interpreter::leave_call(std::size_t line, std::string_view raw_line) {
  detail::ExecState& st = *state_;
  if (st.save_slots.size() <= 1) return;
  const detail::SaveSlot slot = st.save_slots.back();
  st.save_slots.pop_back();
  if (slot.valid && slot.autorestore) {
    const BlockContext ctx{st.file, line, raw_line};
    detail::restore_modes(st, slot.modes, ctx, nullptr);
  }
}

ABBE_HOT void Interpreter::execute_evaluated(const Block& written, std::string_view raw_line,
                                             const MotionSink& sink) {
  detail::ExecState& st = *state_;
  if (st.ended) return;
  const BlockContext ctx{st.file, written.line, raw_line};
  if (st.config.dialect.dialect == Dialect::linuxcnc && !st.text_seen) {
    // rs274ngc: a '%' as the first non-blank line opens a tape that the next
    // '%' ends; a '%' anywhere else is an error.
    if (raw_line.find_first_not_of(" \t\r") != std::string_view::npos) st.text_seen = true;
    if (written.percent) {
      st.percent_opened = true;
      return;
    }
  }
  if (written.percent) {
    if (st.config.dialect.dialect == Dialect::linuxcnc) {
      if (!st.percent_opened)
        ctx.fail(nullptr,
                 "'%' after the start of the program (rs274ngc allows '%' only as the first "
                 "line and as the end of such a program)");
      st.ended = true;
    }
    return;
  }
  if (written.words.empty()) return;
  // read
  const Block* source = &written;
  if (st.config.dialect.dialect == Dialect::fanuc) {
    st.adapted = written;
    detail::adapt_fanuc_block(st.adapted, raw_line, st.inch, st.config.dialect.integers, ctx);
    source = &st.adapted;
  }
  const Block& block = *source;
  st.read_block = source;
  const BlockCodes codes = classify_block(block, ctx);
  // check
  st.read_non_modal = -1;
  const bool plain = detail::is_plain_block(st, codes);
  const detail::BlockPlan b =
      plain ? detail::plan_plain_block(st, codes, ctx) : detail::plan_block(st, codes, ctx);
  st.read_non_modal = b.non_modal;
  if (!plain) {
    if (codes.has_rotary_word()) detail::check_rotary_words(st, b);
    detail::check_comp_block(st, b);
  }

  // convert, in rs274ngc's order of execution. Every step before the motion
  // acts only on a code of its group (G or M); a block whose only G code is
  // a motion code and that has no M code (most of a CAM program) needs only
  // its F, S, T words and the motion.
  constexpr std::uint32_t kMotionGroup = 1U << static_cast<unsigned>(GGroup::motion);
  const bool modes = (codes.g_mask & ~kMotionGroup) != 0 || codes.m_mask != 0;
  if (!modes && (codes.has('F') || codes.has('S') || codes.has('T')))
    detail::convert_feed_speed_tool(st, b);

  // The plain block's one motion goes from its end point to the sink
  // directly; what it skips acts only on codes, words or compensation
  // states it cannot have.
  if (plain && b.motion != -1 && st.comp.queue.empty() && !st.comp.exit_pending) {
    detail::convert_plain_motion(st, b, block, sink);
    return;
  }

  std::uint32_t sub = 0;
  auto deliver = [&](Motion& m) { detail::deliver_motion(st, m, block, ctx, sink); };
  st.deliver = detail::make_hook(deliver);
  auto stamp = [&](Motion& m) { detail::stamp_motion(st, m, block.line, sub++); };
  st.stamp = detail::make_hook(stamp);
  auto emit_motion = [&](Motion& m) {
    stamp(m);
    if (!st.comp.queue.empty()) {  // after the motions compensation holds back
      detail::comp_enqueue_dwell(st, m);
      return;
    }
    if (st.comp.exit_pending && m.kind != MotionKind::dwell) {
      // The first move after G40 starts where the compensated tool stands.
      m.start = st.comp.exit_nose_mm - Eigen::Vector3d(0, 0, st.active_length_mm());
      st.comp.exit_pending = false;
    }
    deliver(m);
  };
  const detail::Emit emit = detail::make_hook(emit_motion);

  if (modes) {
    // Every step acts only on the codes of its own groups (its first test);
    // a step whose groups the block does not use is not called.
    const auto g = [&codes](GGroup group) { return codes.group(group) != nullptr; };
    const auto m = [&codes](MGroup group) { return codes.group(group) != nullptr; };
    if (g(GGroup::feed_mode)) detail::convert_feed_mode(st, b);
    detail::convert_feed_speed_tool(st, b);
    if (m(MGroup::modal_save)) detail::convert_modal_save(st, b);
    if (g(GGroup::non_modal)) detail::convert_dwell(st, b, emit);
    if (g(GGroup::plane)) detail::convert_plane(st, b);
    if (g(GGroup::units)) detail::convert_units(st, b);
    if (g(GGroup::cutter_comp)) detail::convert_cutter_comp(st, b);
    if (g(GGroup::tool_length)) detail::convert_tool_length(st, b);
    if (g(GGroup::coord_system)) detail::convert_coord_system(st, b);
    if (g(GGroup::path_control)) detail::convert_path_control(st, b);
    if (g(GGroup::distance) || g(GGroup::arc_distance) || g(GGroup::retract))
      detail::convert_distance_modes(st, b);
    if (g(GGroup::non_modal)) {
      detail::convert_setup(st, b);
      detail::convert_home(st, b, emit);
      detail::convert_axis_offsets(st, b);
    }
  }
  detail::convert_motion(st, b, emit);
  if (modes && codes.group(MGroup::stopping)) detail::convert_stop(st, b);
}

}  // namespace abbe::gcode
