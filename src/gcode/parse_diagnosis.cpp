#include "parse_diagnosis.hpp"

#include <fmt/format.h>

#include <array>

#include "grammar/gcode.hpp"

namespace abbe::gcode::detail {

namespace {

bool is_blank(char c) { return c == ' ' || c == '\t'; }
bool is_digit(char c) { return c >= '0' && c <= '9'; }
bool is_alpha(char c) { return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z'); }
char upper(char c) { return (c >= 'a' && c <= 'z') ? static_cast<char>(c - 'a' + 'A') : c; }

std::size_t skip_blanks(std::string_view s, std::size_t i) {
  while (i < s.size() && is_blank(s[i])) ++i;
  return i;
}

bool starts_with_nocase(std::string_view s, std::size_t i, std::string_view word) {
  if (s.size() - i < word.size()) return false;
  for (std::size_t k = 0; k < word.size(); ++k)
    if (upper(s[i + k]) != upper(word[k])) return false;
  return true;
}

// Printable form of a short piece of the line for a message (no control bytes).
std::string quoted(std::string_view text) {
  constexpr std::size_t kMax = 24;
  std::string out;
  for (char c : text.substr(0, kMax)) {
    const auto u = static_cast<unsigned char>(c);
    out += (u < 0x20 || u >= 0x7f) ? '?' : c;
  }
  if (text.size() > kMax) out += "...";
  return "'" + out + "'";
}

// Keywords of LinuxCNC O-word control flow (o100 sub, o101 if [...], ...).
bool is_o_word_keyword(std::string_view word) {
  static constexpr std::array<std::string_view, 15> kKeywords = {
      "sub",    "endsub", "call",  "return", "do",       "while",  "endwhile", "if",
      "elseif", "else",   "endif", "break",  "continue", "repeat", "endrepeat"};
  for (auto k : kKeywords)
    if (word.size() == k.size() && starts_with_nocase(word, 0, k)) return true;
  return false;
}

bool only_block_delete_before(const ast::Line& items) {
  return items.items == 0 || (items.items == 1 && items.last_head == '/');
}

// A word letter at `at` whose number did not parse: say what is wrong with it.
std::string explain_word_number(std::string_view line, std::size_t at, std::size_t& column) {
  const char letter = upper(line[at]);
  std::size_t i = skip_blanks(line, at + 1);
  std::size_t after_sign = i;
  if (after_sign < line.size() && (line[after_sign] == '+' || line[after_sign] == '-'))
    after_sign = skip_blanks(line, after_sign + 1);
  if (after_sign < line.size() && line[after_sign] == '#') {
    column = after_sign;
    return fmt::format("bad parameter in word '{}' (#n, #<name> or #[expression])", letter);
  }
  if (after_sign < line.size() && line[after_sign] == '[') {
    column = after_sign;
    return fmt::format("bad expression in word '{}'", letter);
  }
  if (starts_with_nocase(line, after_sign, "nan") || starts_with_nocase(line, after_sign, "inf")) {
    column = after_sign;
    return fmt::format("NaN and infinity are not numbers (word '{}')", letter);
  }
  // The text that looks like a number: digits, '.', signs, exponent letters.
  std::size_t end = i;
  while (end < line.size()) {
    const char c = line[end];
    if (is_digit(c) || c == '.' || c == '+' || c == '-' || c == 'e' || c == 'E') {
      ++end;
    } else if (is_blank(c) && end > i && (line[end - 1] == '+' || line[end - 1] == '-')) {
      ++end;  // blanks after a sign belong to the number
    } else {
      break;
    }
  }
  const std::string_view text = line.substr(i, end - i);
  bool has_digit = false;
  bool has_exponent = false;
  for (std::size_t k = 0; k < text.size(); ++k) {
    if (is_digit(text[k])) has_digit = true;
    if ((text[k] == 'e' || text[k] == 'E') && has_digit) has_exponent = true;
  }
  if (!has_digit && text.find('.') == std::string_view::npos) {
    column = at;
    return fmt::format("word '{}' has no number", letter);
  }
  column = i;
  if (has_exponent)
    return fmt::format("bad number {} in word '{}': exponents are not supported", quoted(text),
                       letter);
  return fmt::format("bad number {} in word '{}'", quoted(text), letter);
}

std::string explain_letter(std::string_view line, std::size_t stop, const ast::Line& items,
                           std::size_t& column) {
  const char letter = upper(line[stop]);
  column = stop;
  switch (letter) {
    case 'U':
    case 'V':
    case 'W':
      return fmt::format("axis word '{}' is not supported (3-axis machine)", letter);
    case 'O': {
      const std::size_t i = skip_blanks(line, stop + 1);
      if (!only_block_delete_before(items)) return "an O-word must be the first word of its line";
      if (i < line.size() && line[i] == '<')
        return "bad O-word: o<name> must be followed by sub, endsub, return, call, if, elseif, "
               "else, endif, do, while, endwhile, repeat, endrepeat, break or continue and its "
               "[...] arguments";
      if (i < line.size() && is_digit(line[i])) {
        column = i;
        return "bad program number: the O-number must be an integer";
      }
      return "word 'O' has no number";
    }
    case 'N': {
      if (!only_block_delete_before(items))
        return "a line number (N) must be the first word of its block";
      const std::size_t i = skip_blanks(line, stop + 1);
      if (i < line.size() && (is_digit(line[i]) || line[i] == '.')) {
        column = i;
        return "bad line number: N must be followed by an integer";
      }
      return "word 'N' has no number";
    }
    default:
      return explain_word_number(line, stop, column);
  }
}

}  // namespace

InputError line_error(std::string_view line, std::size_t line_number, const std::string& file,
                      std::size_t offset, const std::string& message) {
  return InputError(SourceLocation{file, line_number, offset + 1, "", std::string(line)}, message);
}

InputError explain_parse_stop(std::string_view line, std::size_t stop, const ast::Line& items,
                              std::size_t line_number, const std::string& file) {
  std::size_t column = stop;
  std::string message;
  const char c = line[stop];
  const auto u = static_cast<unsigned char>(c);
  const char previous = upper(items.last_head);  // '\0' if no item

  if (previous == '*') {
    message = "the checksum (*nn) must be the last thing on its line";
  } else if (previous == '%') {
    message = "only a comment may follow '%' (tape delimiter) on its line";
  } else if (items.block != nullptr && items.block->o.keyword != OKeyword::none) {
    message = "bad O-word line: only [...] arguments and a comment may follow its keyword";
  } else if (items.program_number_head != nullptr) {
    std::size_t end = stop;
    while (end < line.size() && is_alpha(line[end])) ++end;
    if (is_o_word_keyword(line.substr(stop, end - stop)) || c == '<' || c == '[') {
      column = static_cast<std::size_t>(items.program_number_head - line.data());
      message = "bad O-word line: only [...] arguments and a comment may follow its keyword";
    } else {
      message = "a program number line (O...) may carry only a comment";
    }
  } else if (items.words_and_comments >= grammar::kMaxItemsPerBlock) {
    message = fmt::format("too many words in one block (more than {})", grammar::kMaxItemsPerBlock);
  } else if (is_alpha(c) || c == '@' || c == '^') {
    message = explain_letter(line, stop, items, column);
  } else if (is_digit(c) || c == '.' || c == '+' || c == '-') {
    // Items that end with a number: all but '/', '%' and comments.
    const bool after_number = items.items > 0 && stop > 0 && is_blank(line[stop - 1]) &&
                              previous != '/' && previous != '%' && previous != '(' &&
                              previous != ';';
    if (after_number && (is_digit(c) || c == '.'))
      message = "a blank inside a number is not supported";
    else
      message = fmt::format("number {} without a word letter", quoted(line.substr(stop, 12)));
  } else {
    switch (c) {
      case '#':
        message = "bad parameter setting (#n = value or #<name> = value)";
        break;
      case '[':
        message = "an expression ([...]) must be the value of a word";
        break;
      case '(': {
        const std::size_t next = line.find_first_of("()", stop + 1);
        if (next != std::string_view::npos && line[next] == '(') {
          column = next;
          message = "nested comments are not supported: '(' inside a comment";
        } else {
          message = "unclosed comment: '(' without a matching ')'";
        }
        break;
      }
      case ')':
        message = "')' without a matching '('";
        break;
      case '/':
        message = "block delete '/' must be the first character of its line";
        break;
      case '%':
        message = "'%' (tape delimiter) must stand alone on its line";
        break;
      case '*':
        message = "bad checksum: '*' must be followed by digits and end the line";
        break;
      case '<':
        message = "named parameters (<...>) are not supported";
        break;
      case '\r':
        message = "unexpected byte 0x0d (carriage return inside a line)";
        break;
      default:
        if (u < 0x20 || u >= 0x7f)
          message = fmt::format("unexpected byte 0x{:02x}", static_cast<unsigned>(u));
        else
          message = fmt::format("unexpected character '{}'", c);
    }
  }
  return line_error(line, line_number, file, column, message);
}

}  // namespace abbe::gcode::detail
