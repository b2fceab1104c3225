#pragma once
// BlockEditor: rewrites one block of a program in place — replaces the
// number of a written word, inserts a word after the block's last
// axis/centre/radius word, deletes a word — and keeps every other byte of
// the raw line (compensate's rule: only corrected coordinates change).
#include <cstdint>
#include <string>
#include <vector>

#include "abbe/compensate/number_format.hpp"
#include "abbe/gcode/block.hpp"

namespace abbe::compensate::detail {

// Appends "<sep><letter><value>" in the given style (a new word: the default style).
void append_word(std::string& line, const char* sep, char letter, double value,
                 const NumberStyle& style, int decimals);

// The block's word of `letter`, nullptr if it has none.
const gcode::Word* find_word(const gcode::Block& b, char letter);

class BlockEditor {
 public:
  // `decimals`: most decimals of a corrected number; `plain`: the style of
  // words written anew. `block` and `raw` must outlive the editor.
  BlockEditor(const gcode::Block& block, const std::string& raw, int decimals,
              const NumberStyle& plain);

  // Sets the number of `letter` to `target` (program units). A written word
  // keeps its bytes when the rounded value does not change; an absent word
  // is inserted when `target` differs from `baseline` (what the block means
  // without it) at the output precision. Returns the value now in effect.
  double set(char letter, double target, double baseline, bool may_insert);
  // Deletes a word (and the blank before it).
  void remove(char letter);
  // Inserts `text` (a word) before the first axis/centre/radius word.
  void insert_before_axes(const std::string& text);

  bool changed() const { return !edits_.empty(); }
  bool spaced() const { return spaced_; }  // words separated by blanks
  std::string apply() const;               // the rewritten line

 private:
  struct Edit {
    std::uint32_t begin = 0, end = 0;  // begin == end: insertion
    std::string text;
  };
  const gcode::Block& block_;
  const std::string& raw_;
  int decimals_;
  NumberStyle plain_;
  std::uint32_t anchor_ = 0, anchor_any_ = 0;
  bool spaced_ = true;
  std::vector<Edit> edits_;
};

}  // namespace abbe::compensate::detail
