#include "abbe/machine/kinematic_chain.hpp"

#include <fmt/format.h>

#include <cctype>
#include <stdexcept>
#include <vector>

namespace abbe::machine {

KinematicChain KinematicChain::parse(const std::string& text) {
  // Tokens are single letters, each optionally followed by primes; blanks
  // between them are optional ("w X' b Y Z t" and "wX'bYZt" are the same).
  std::vector<std::string> tokens;
  for (const char c : text) {
    if (std::isspace(static_cast<unsigned char>(c))) continue;
    if (c == '\'' && !tokens.empty())
      tokens.back() += c;
    else
      tokens.emplace_back(1, c);
  }
  auto fail = [&](const std::string& why) {
    throw std::invalid_argument(fmt::format(
        "invalid kinematic chain \"{}\": {} (expected e.g. \"w X' b Y Z t\": `w` first, "
        "`t` last, one `b`, each of X, Y, Z once)",
        text, why));
  };
  if (tokens.size() != 6)
    fail(fmt::format("{} tokens instead of 6 (w, b, t and three axes)", tokens.size()));
  if (tokens.front() != "w") fail("the first token must be the workpiece `w`");
  if (tokens.back() != "t") fail("the last token must be the tool `t`");

  KinematicChain chain;
  chain.text_ = text;
  std::array<bool, 3> seen{false, false, false};
  bool bed_seen = false;
  int n_axes = 0;
  bool any_prime = false;
  std::array<bool, 3> primed{false, false, false};
  for (std::size_t i = 1; i + 1 < tokens.size(); ++i) {
    const std::string& tok = tokens[i];
    if (tok == "b") {
      if (bed_seen) fail("more than one bed `b`");
      bed_seen = true;
      continue;
    }
    bool prime = tok.size() == 2 && tok[1] == '\'';
    auto axis = parse_axis(prime ? tok.substr(0, 1) : tok);
    if (!axis) fail(fmt::format("unknown token \"{}\"", tok));
    if (seen[index(*axis)]) fail(fmt::format("axis {} appears twice", axis_letter(*axis)));
    seen[index(*axis)] = true;
    if (n_axes >= 3) fail("more than three axes");
    chain.order_[static_cast<std::size_t>(n_axes++)] = *axis;
    chain.workpiece_side_[index(*axis)] = !bed_seen;
    primed[index(*axis)] = prime;
    any_prime = any_prime || prime;
  }
  if (!bed_seen) fail("no bed `b`");
  if (n_axes != 3) fail("it needs each of X, Y, Z exactly once");
  if (any_prime) {
    for (Axis a : kAxes)
      if (primed[index(a)] != chain.workpiece_side_[index(a)])
        fail(fmt::format("axis {} is {} but {}primed (primes mark exactly the axes left of `b`)",
                         axis_letter(a),
                         chain.workpiece_side_[index(a)] ? "workpiece-side" : "tool-side",
                         primed[index(a)] ? "" : "not "));
  }

  // U(j) from the chain positions.
  for (int pj = 0; pj < 3; ++pj) {
    Axis j = chain.order_[static_cast<std::size_t>(pj)];
    for (int pi = 0; pi < 3; ++pi) {
      Axis i = chain.order_[static_cast<std::size_t>(pi)];
      bool m;
      if (chain.workpiece_side_[index(j)])
        m = chain.workpiece_side_[index(i)] && pi < pj;  // axes between w and j
      else
        m = chain.workpiece_side_[index(i)] || pi <= pj;  // j, tool-side carriers, workpiece side
      chain.moves_[index(j)][index(i)] = m;
    }
  }
  return chain;
}

std::array<double, 3> KinematicChain::moves_mask(Axis j) const {
  std::array<double, 3> m{};
  for (Axis i : kAxes) m[static_cast<std::size_t>(index(i))] = moves(j, i) ? 1.0 : 0.0;
  return m;
}

}  // namespace abbe::machine
