#include "word_use.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cstdint>

#include "interpreter_steps.hpp"

namespace abbe::gcode::detail {

const std::vector<WordUse>& word_use_table() {
  static const std::vector<WordUse> table{
      {'I', {gcode_id(2), gcode_id(3), gcode_id(87)}, false},
      {'J', {gcode_id(2), gcode_id(3), gcode_id(87)}, false},
      {'K', {gcode_id(2), gcode_id(3), gcode_id(87)}, false},
      {'R', {gcode_id(2), gcode_id(3), gcode_id(10)}, true},
      {'P',
       {gcode_id(2), gcode_id(3), gcode_id(4), gcode_id(10), gcode_id(64), gcode_id(74),
        gcode_id(82), gcode_id(84), gcode_id(86), gcode_id(89)},
       false},
      {'Q', {gcode_id(64), gcode_id(73), gcode_id(83)}, false},
      {'L', {gcode_id(10), gcode_id(41, 1), gcode_id(42, 1)}, true},
      {'H', {gcode_id(43), gcode_id(43, 2)}, false},
      {'D', {gcode_id(41), gcode_id(42), gcode_id(41, 1), gcode_id(42, 1)}, false},
  };
  return table;
}

std::string word_users(const WordUse& use) {
  std::vector<std::string> names;
  for (int code : use.codes) names.push_back(gcode_name(code));
  if (use.canned_cycles) names.emplace_back("canned cycle");
  std::string text;
  for (std::size_t i = 0; i < names.size(); ++i) {
    if (i > 0) text += i + 1 == names.size() ? " or " : ", ";
    text += names[i];
  }
  return text;
}

namespace {

constexpr std::uint32_t letter_bit(char letter) { return 1U << BlockCodes::letter_index(letter); }

// word_use_table() turned around, built once: the table's letters, and per
// G code (gcode_id, 0..10000) the letters it consumes. A block whose table
// letters are all consumed by its codes (most blocks) needs no table walk.
struct ConsumedLetters {
  static constexpr int kMaxCode = 10000;
  std::uint32_t table = 0;
  std::vector<std::uint32_t> by_code = std::vector<std::uint32_t>(kMaxCode + 1, 0U);
  ConsumedLetters() {
    for (const WordUse& use : word_use_table()) {
      const std::uint32_t bit = letter_bit(use.letter);
      table |= bit;
      for (int code : use.codes) by_code[static_cast<std::size_t>(code)] |= bit;
      if (use.canned_cycles)
        for (int code = 0; code <= kMaxCode; ++code)
          if (is_cycle(code)) by_code[static_cast<std::size_t>(code)] |= bit;
    }
  }
};

const ConsumedLetters& consumed_letters() {
  static const ConsumedLetters consumed;
  return consumed;
}

}  // namespace

void check_word_use(const BlockCodes& codes, const BlockContext& ctx,
                    std::initializer_list<int> active) {
  const ConsumedLetters& consumed = consumed_letters();
  const std::uint32_t present = codes.letter_mask & consumed.table;
  if (present == 0) return;
  // M codes that read a word: M50-M53 P (override on/off), M61 Q (tool).
  const auto* overrides = codes.group(MGroup::overrides);
  const auto* tool_change = codes.group(MGroup::tool_change);
  const bool m_reads_p = overrides && overrides->code >= 50 && overrides->code <= 53;
  const bool m_reads_q = tool_change && tool_change->code == 61;
  std::uint32_t used_letters =
      (m_reads_p ? letter_bit('P') : 0U) | (m_reads_q ? letter_bit('Q') : 0U);
  for (int code : active)
    if (code >= 0 && code <= ConsumedLetters::kMaxCode)
      used_letters |= consumed.by_code[static_cast<std::size_t>(code)];
  if ((present & ~used_letters) == 0) return;
  // A word no code uses: the first in the table's order, named with its users.
  for (const WordUse& use : word_use_table()) {
    if (!codes.has(use.letter)) continue;
    if ((use.letter == 'P' && m_reads_p) || (use.letter == 'Q' && m_reads_q)) continue;
    bool used = false;
    for (int code : active) {
      if (code < 0) continue;
      used = used || (use.canned_cycles && is_cycle(code)) ||
             std::find(use.codes.begin(), use.codes.end(), code) != use.codes.end();
    }
    if (!used)
      ctx.fail(codes.word(use.letter),
               fmt::format("{} word with no {} to use it", use.letter, word_users(use)));
  }
}

}  // namespace abbe::gcode::detail
