#pragma once
// KinematicChain: the ISO 10791-1 chain string of a 3-axis machine, e.g.
// "w X' b Y Z t" — workpiece left, tool right, `b` the bed. Axes left of
// `b` move the workpiece, axes right of it move the tool.
#include <array>
#include <string>

#include "abbe/machine/axis.hpp"

namespace abbe::machine {

class KinematicChain {
 public:
  // Throws std::invalid_argument with a message saying what is wrong (the
  // machine loader turns it into an InputError naming the file and line).
  static KinematicChain parse(const std::string& text);

  const std::string& text() const { return text_; }
  // The axes in chain order as written from `w` to `t`.
  const std::array<Axis, 3>& order() const { return order_; }
  bool workpiece_side(Axis j) const { return workpiece_side_[index(j)]; }
  // U(j): the axes whose positions move the carriage of axis j relative to
  // the workpiece (see docs/models.md). For a tool-side j: j itself, the
  // tool-side axes that carry j, and every workpiece-side axis; for a
  // workpiece-side j: the workpiece-side axes that j carries.
  bool moves(Axis j, Axis i) const { return moves_[index(j)][index(i)]; }
  // The same as 0/1 factors per coordinate, for arithmetic.
  std::array<double, 3> moves_mask(Axis j) const;

 private:
  std::string text_;
  std::array<Axis, 3> order_{Axis::x, Axis::y, Axis::z};
  std::array<bool, 3> workpiece_side_{false, false, false};
  std::array<std::array<bool, 3>, 3> moves_{};
};

}  // namespace abbe::machine
