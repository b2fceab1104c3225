// convert_home: G28 / G30 (return to a stored position through an
// intermediate point) and G28.1 / G30.1 (store the current position), as
// rs274ngc's convert_home does them.
#include <fmt/format.h>

#include "interpreter_steps.hpp"

namespace abbe::gcode::detail {

void convert_home(ExecState& st, const BlockPlan& b, const Emit& emit) {
  const int code = b.non_modal;
  if (code == gcode_id(28, 1) || code == gcode_id(30, 1)) {
    Eigen::Vector3d& stored = code == gcode_id(28, 1) ? st.g28_home : st.g30_home;
    stored = st.nose(st.pos) * st.unit();
    return;
  }
  if (code != gcode_id(28) && code != gcode_id(30)) return;
  static constexpr char kAxisLetters[3] = {'X', 'Y', 'Z'};
  const BlockCodes& c = b.codes;
  // The intermediate point: the axis words in the current distance mode.
  Eigen::Vector3d via = st.pos;
  for (int a = 0; a < 3; ++a)
    if (const Word* w = c.word(kAxisLetters[a]))
      via[a] = st.incremental ? st.pos[a] + w->value : w->value;
  auto traverse = [&](const Eigen::Vector3d& target) {
    Motion m;
    m.kind = MotionKind::rapid;
    m.start = st.tip(st.pos);
    m.end = st.tip(target);
    st.pos = target;
    emit(m);
  };
  traverse(via);
  // The stored position (machine coordinates of the spindle nose, mm) in the
  // program frame; only the axes written move there, all three if none is.
  const Eigen::Vector3d& stored = code == gcode_id(28) ? st.g28_home : st.g30_home;
  const Eigen::Vector3d home = st.pos + stored / st.unit() - st.nose(st.pos);
  const bool all = !c.has('X') && !c.has('Y') && !c.has('Z');
  Eigen::Vector3d end = st.pos;
  for (int a = 0; a < 3; ++a)
    if (all || c.has(kAxisLetters[a])) end[a] = home[a];
  traverse(end);
}

}  // namespace abbe::gcode::detail
