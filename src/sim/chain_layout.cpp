#include "abbe/sim/chain_layout.hpp"

#include <cctype>
#include <stdexcept>

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
  // Tokens: w, b, t, X, Y, Z, each axis optionally primed; blanks between are optional.
  struct Token {
    char c;
    bool primed;
  };
  std::vector<Token> tokens;
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (std::isspace(static_cast<unsigned char>(c))) continue;
    if (c == '\'') {
      if (tokens.empty() || axis_index(tokens.back().c) < 0 || tokens.back().primed)
        throw std::invalid_argument("chain \"" + text + "\": a prime must follow an axis letter");
      tokens.back().primed = true;
      continue;
    }
    if (c != 'w' && c != 'b' && c != 't' && c != 'X' && c != 'Y' && c != 'Z')
      throw std::invalid_argument("chain \"" + text + "\": unexpected character '" +
                                  std::string(1, c) + "' (expected w, b, t, X, Y, Z or ')");
    tokens.push_back({c, false});
  }
  if (tokens.size() != 6 || tokens.front().c != 'w' || tokens.back().c != 't')
    throw std::invalid_argument("chain \"" + text +
                                "\": expected w, b, t and each of X, Y, Z once, w first, t last");
  ChainLayout out{Empty{}};
  out.text_ = text;
  int b_pos = -1;
  std::array<int, 3> pos{-1, -1, -1};
  int n_axes = 0;
  for (int k = 1; k < 5; ++k) {
    const Token& tok = tokens[static_cast<std::size_t>(k)];
    if (tok.c == 'b') {
      if (b_pos >= 0) throw std::invalid_argument("chain \"" + text + "\": more than one b");
      b_pos = k;
      continue;
    }
    const int j = axis_index(tok.c);
    if (j < 0 || pos[static_cast<std::size_t>(j)] >= 0)
      throw std::invalid_argument("chain \"" + text + "\": each of X, Y, Z must appear once");
    pos[static_cast<std::size_t>(j)] = k;
    out.order_[static_cast<std::size_t>(n_axes++)] = j;
  }
  if (b_pos < 0) throw std::invalid_argument("chain \"" + text + "\": missing b");
  bool any_prime = false;
  for (const Token& tok : tokens) any_prime = any_prime || tok.primed;
  for (int j = 0; j < 3; ++j) {
    const auto ju = static_cast<std::size_t>(j);
    out.workpiece_side_[ju] = pos[ju] < b_pos;
    const bool primed = tokens[static_cast<std::size_t>(pos[ju])].primed;
    if (any_prime && primed != out.workpiece_side_[ju])
      throw std::invalid_argument("chain \"" + text +
                                  "\": primes must mark exactly the workpiece-side axes");
  }
  for (int j = 0; j < 3; ++j) {
    const auto ju = static_cast<std::size_t>(j);
    for (int i = 0; i < 3; ++i) {
      const auto iu = static_cast<std::size_t>(i);
      bool m = false;
      if (out.workpiece_side_[ju]) {
        // Workpiece side: the workpiece-side axes j carries (between w and j).
        m = out.workpiece_side_[iu] && pos[iu] < pos[ju];
      } else {
        // Tool side: j, the tool-side axes that carry j, every workpiece-side axis.
        m = i == j || out.workpiece_side_[iu] || pos[iu] < pos[ju];
      }
      out.moves_[ju][iu] = m;
    }
  }
  return out;
}

}  // namespace abbe::sim
