#include "block_editor.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <string_view>

namespace abbe::compensate::detail {

void append_word(std::string& line, const char* sep, char letter, double value,
                 const NumberStyle& style, int decimals) {
  line += sep;
  line += letter;
  append_number(line, value, style, decimals);
}

const gcode::Word* find_word(const gcode::Block& b, char letter) {
  for (const auto& w : b.words)
    if (w.letter == letter) return &w;
  return nullptr;
}

BlockEditor::BlockEditor(const gcode::Block& block, const std::string& raw, int decimals,
                         const NumberStyle& plain)
    : block_(block), raw_(raw), decimals_(decimals), plain_(plain) {
  // Inserted words go right after the last axis/centre/radius word, or the last word.
  for (const auto& w : block.words) {
    if (std::string_view("XYZIJKR").find(w.letter) != std::string_view::npos) anchor_ = w.end;
    anchor_any_ = std::max(anchor_any_, w.end);
  }
  if (anchor_ == 0) anchor_ = anchor_any_;
  spaced_ = raw.find(' ') != std::string::npos || block.words.size() < 2;
}

double BlockEditor::set(char letter, double target, double baseline, bool may_insert) {
  if (const gcode::Word* w = find_word(block_, letter)) {
    const std::string_view text(raw_.data() + w->number_begin, w->end - w->number_begin);
    NumberStyle style = number_style(text);
    style.point_always = plain_.point_always;
    const int d = std::max(style.decimals, decimals_);
    if (round_to(target, d) == round_to(w->value, d)) return w->value;
    edits_.push_back({w->number_begin, w->end, format_number(target, style, decimals_)});
    return round_to(target, d);
  }
  if (!may_insert || round_to(target, decimals_) == round_to(baseline, decimals_)) return baseline;
  edits_.push_back({anchor_, anchor_,
                    fmt::format("{}{}{}", spaced_ ? " " : "", letter,
                                format_number(target, plain_, decimals_))});
  return round_to(target, decimals_);
}

void BlockEditor::remove(char letter) {
  const gcode::Word* w = find_word(block_, letter);
  if (!w) return;
  std::uint32_t b = w->begin;
  if (b > 0 && raw_[b - 1] == ' ') --b;
  edits_.push_back({b, w->end, ""});
}

void BlockEditor::insert_before_axes(const std::string& text) {
  std::uint32_t at = anchor_any_;
  for (const auto& w : block_.words)
    if (std::string_view("XYZIJKR").find(w.letter) != std::string_view::npos) {
      at = w.begin;
      break;
    }
  edits_.push_back({at, at, spaced_ ? text + " " : text});
}

std::string BlockEditor::apply() const {
  std::vector<Edit> e = edits_;
  std::stable_sort(e.begin(), e.end(),
                   [](const Edit& a, const Edit& b) { return a.begin < b.begin; });
  std::string out;
  std::uint32_t pos = 0;
  for (const auto& x : e) {
    out.append(raw_, pos, x.begin - pos);
    out += x.text;
    pos = x.end;
  }
  out.append(raw_, pos, std::string::npos);
  return out;
}

}  // namespace abbe::compensate::detail
