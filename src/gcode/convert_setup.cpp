// convert_setup: G10 — tool data (L1, L10) and work offsets (L2, L20) set
// from the program, as rs274ngc's convert_setup and convert_setup_tool do.
#include <fmt/format.h>

#include <cmath>

#include "interpreter_steps.hpp"

namespace abbe::gcode::detail {

namespace {

constexpr char kAxisLetters[3] = {'X', 'Y', 'Z'};

void set_tool(ExecState& st, const BlockPlan& b, int l) {
  const BlockCodes& c = b.codes;
  const Word* p = c.word('P');
  if (p->value < 1.0 || !is_integer(p->value))
    b.ctx.fail(p, fmt::format("P word (tool number) of G10 L{} must be a positive integer", l));
  for (char a : {'X', 'Y'})
    if (c.has(a))
      b.ctx.fail(c.word(a), fmt::format("{} offset of a tool (G10 L{} {}) is not supported "
                                        "(tool length along Z only)",
                                        a, l, a));
  const int tool = static_cast<int>(std::lround(p->value));
  // R: the cutter radius (cutter radius compensation, G41/G42).
  if (const Word* r = c.word('R')) st.config.tool_diameters[tool] = 2.0 * r->value * st.unit();
  const Word* z = c.word('Z');
  if (!z) return;
  // L1: the length written; L10: the length that makes the current Z read Z.
  const double length = l == 1 ? z->value : st.pos.z() + st.tlo - z->value;
  st.config.tool_lengths[tool] = length * st.unit();
}

void set_work_offset(ExecState& st, const BlockPlan& b, int l) {
  const BlockCodes& c = b.codes;
  const Word* p = c.word('P');
  if (!is_integer(p->value) || p->value < 0.0 || p->value > 9.0)
    b.ctx.fail(p, fmt::format("P word (coordinate system) of G10 L{} must be 0 to 9", l));
  const int system = static_cast<int>(std::lround(p->value));
  if (system > 6)
    b.ctx.fail(
        p, fmt::format("coordinate system beyond G59 (G10 L{} P{}) is not supported", l, system));
  if (const Word* r = c.word('R'))
    if (r->value != 0.0)
      b.ctx.fail(r, fmt::format("coordinate system rotation (G10 L{} R) is not supported", l));
  const auto index = static_cast<std::size_t>(system == 0 ? st.coord_index : system - 1);
  const Eigen::Vector3d before = st.g5x();
  Eigen::Vector3d offset = st.work_offsets[index] / st.unit();  // program units
  for (int a = 0; a < 3; ++a)
    if (const Word* w = c.word(kAxisLetters[a]))
      offset[a] = l == 2 ? w->value : st.pos[a] + before[a] - w->value;
  st.work_offsets[index] = offset * st.unit();
  if (static_cast<int>(index) == st.coord_index) st.pos += before - st.g5x();
}

}  // namespace

void convert_setup(ExecState& st, const BlockPlan& b) {
  if (b.non_modal != gcode_id(10)) return;
  const BlockCodes& c = b.codes;
  const Word* at = c.group(GGroup::non_modal)->word;
  const Word* lw = c.word('L');
  if (!lw) b.ctx.fail(at, "G10 without an L word (L1, L2, L10 or L20)");
  if (!c.has('P')) b.ctx.fail(at, "G10 without a P word");
  const int l = is_integer(lw->value) ? static_cast<int>(std::lround(lw->value)) : -1;
  switch (l) {
    case 1:
    case 10:
      set_tool(st, b, l);
      return;
    case 2:
    case 20:
      set_work_offset(st, b, l);
      return;
    case 11:
      b.ctx.fail(lw, "tool data relative to a fixture (G10 L11) is not supported");
    default:
      b.ctx.fail(lw, "G10 needs L1, L2, L10 or L20");
  }
}

}  // namespace abbe::gcode::detail
