#pragma once
// Which words each code consumes (rs274ngc refuses a word that no code of
// its block uses): I, J, K need an arc; R an arc or a canned cycle; P an arc
// (turns), G4, G64, G82 or G89; Q G64, G73 or G83; L a canned cycle; H G43.
// One table, checked in its order; the message names the codes that would
// have used the word ("P word with no G2, G3, G4, G64, G82 or G89 to use it").
#include <initializer_list>
#include <string>
#include <vector>

#include "abbe/gcode/modal_groups.hpp"

namespace abbe::gcode::detail {

struct WordUse {
  char letter;
  std::vector<int> codes;  // gcode_ids that consume the word
  bool canned_cycles;      // every canned cycle consumes it too
};

const std::vector<WordUse>& word_use_table();

// "G2, G3 or canned cycle": who could have used the word.
std::string word_users(const WordUse& use);

// Throws (ctx.fail) at the first word of the block that none of `active`
// (the gcode_ids the block executes: its motion, group 0, path control,
// tool length) consumes.
void check_word_use(const BlockCodes& codes, const BlockContext& ctx,
                    std::initializer_list<int> active);

}  // namespace abbe::gcode::detail
