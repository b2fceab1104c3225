#include "abbe/sim/chain_layout.hpp"

#include <cctype>

#include "abbe/machine/kinematic_chain.hpp"

namespace abbe::sim {

char axis_letter(int j) { return "XYZ"[j]; }

int axis_index(char letter) {
  switch (std::toupper(static_cast<unsigned char>(letter))) {
    case 'X':
      return 0;
    case 'Y':
      return 1;
    case 'Z':
      return 2;
    default:
      return -1;
  }
}

ChainLayout::ChainLayout() { *this = parse("w X' b Y Z t"); }

ChainLayout ChainLayout::parse(const std::string& text) {
  // The machine description's parser is the one authority on chain strings.
  const machine::KinematicChain chain = machine::KinematicChain::parse(text);
  ChainLayout out{Empty{}};
  out.text_ = chain.text();
  for (std::size_t k = 0; k < 3; ++k) out.order_[k] = machine::index(chain.order()[k]);
  for (int j = 0; j < 3; ++j) {
    const auto ju = static_cast<std::size_t>(j);
    const auto aj = static_cast<machine::Axis>(j);
    out.workpiece_side_[ju] = chain.workpiece_side(aj);
    for (int i = 0; i < 3; ++i)
      out.moves_[ju][static_cast<std::size_t>(i)] = chain.moves(aj, static_cast<machine::Axis>(i));
  }
  return out;
}

}  // namespace abbe::sim
