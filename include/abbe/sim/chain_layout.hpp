#pragma once
// ChainLayout: the ISO 10791-1 chain of the virtual machine ("w X' b Y Z t")
// and the sets U(j) of axes that move the carriage of axis j relative to the
// workpiece (docs/virtual-machine.md). Axis indices: 0 = X, 1 = Y, 2 = Z.
#include <array>
#include <string>

namespace abbe::sim {

class ChainLayout {
 public:
  ChainLayout();  // "w X' b Y Z t"
  // Throws std::invalid_argument saying what is wrong.
  static ChainLayout parse(const std::string& text);

  const std::string& text() const { return text_; }
  // Axes in chain order as written from `w` to `t`.
  const std::array<int, 3>& order() const { return order_; }
  bool workpiece_side(int j) const { return workpiece_side_[static_cast<std::size_t>(j)]; }
  // i ∈ U(j).
  bool moves(int j, int i) const {
    return moves_[static_cast<std::size_t>(j)][static_cast<std::size_t>(i)];
  }

 private:
  struct Empty {};
  explicit ChainLayout(Empty) {}

  std::string text_;
  std::array<int, 3> order_{0, 1, 2};
  std::array<bool, 3> workpiece_side_{true, false, false};
  std::array<std::array<bool, 3>, 3> moves_{};
};

// "X", "Y", "Z" for 0, 1, 2; and back (−1 if not an axis letter, case-insensitive).
char axis_letter(int j);
int axis_index(char letter);

}  // namespace abbe::sim
