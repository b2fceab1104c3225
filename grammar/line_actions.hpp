#pragma once
// Semantic actions of the line grammar: each one stores a complete item
// (word, comment, N, O, '/', '%', checksum) of the line into the Block of
// the rule's attribute (ast::Line). An action runs only once its item has
// matched completely, and nothing can fail after that, so the Block never
// holds half an item. Numbers are converted here; a number that cannot be
// converted is remembered (the first one) and reported by the caller once
// the whole line is known to be well-formed, as the items come in order.
#include <boost/fusion/include/at_c.hpp>
#include <boost/spirit/home/x3.hpp>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstring>

#include "grammar/ast.hpp"
#include "grammar/gcode.hpp"  // kMaxNumberChars, kMaxProgramNumber

namespace abbe::gcode::grammar {

namespace x3 = boost::spirit::x3;

namespace detail {

inline char upper(char c) { return (c >= 'a' && c <= 'z') ? static_cast<char>(c - 'a' + 'A') : c; }

inline std::uint32_t offset(const ast::Line& line, ast::Iterator it) {
  return static_cast<std::uint32_t>(it - line.line_begin);
}

inline void fail(ast::Line& line, ast::NumberError error, ast::Iterator at) {
  if (line.error == ast::NumberError::none) {
    line.error = error;
    line.error_at = at;
  }
}

inline void count_item(ast::Line& line, char head, bool word_or_comment) {
  ++line.items;
  if (word_or_comment) ++line.words_and_comments;
  line.last_head = head;
}

// The value of a number as the grammar matched it.
inline double value(ast::Line& line, const ast::Number& n) {
  // Fast path (Clinger): an integer mantissa below 2^53 and a power of ten up
  // to 1e22 are exact doubles, so one division rounds correctly and gives the
  // same double as from_chars. Typical CAM numbers (X-123.4567) take it.
  static constexpr double kPow10[] = {1e0,  1e1,  1e2,  1e3,  1e4,  1e5,  1e6,  1e7,
                                      1e8,  1e9,  1e10, 1e11, 1e12, 1e13, 1e14, 1e15,
                                      1e16, 1e17, 1e18, 1e19, 1e20, 1e21, 1e22};
  constexpr std::uint64_t kMaxExactMantissa = std::uint64_t{1} << 53;
  const std::size_t significant = std::size_t{n.digits} + (n.point ? 1 : 0);
  if (significant > kMaxNumberChars) {
    fail(line, ast::NumberError::too_long, n.begin);
    return 0.0;
  }
  if (n.digits <= 19 && n.mantissa <= kMaxExactMantissa && n.fraction <= 22) {
    double result = static_cast<double>(n.mantissa) / kPow10[n.fraction];
    // Negate by setting the sign bit: signs are random, a branch would often miss.
    std::uint64_t bits;
    std::memcpy(&bits, &result, sizeof bits);
    bits |= std::uint64_t{n.negative} << 63;
    std::memcpy(&result, &bits, sizeof bits);
    return result;
  }
  // General case: correctly rounded conversion of the text without blanks and '+'.
  char buffer[kMaxNumberChars + 2];
  std::size_t size = 0;
  for (ast::Iterator c = n.begin; c != n.end; ++c)
    if (*c != ' ' && *c != '\t' && *c != '+') buffer[size++] = *c;
  double result = 0.0;
  const auto [end, ec] = std::from_chars(buffer, buffer + size, result);
  if (ec != std::errc() || end != buffer + size || !std::isfinite(result))
    fail(line, ast::NumberError::out_of_range, n.begin);
  return result;
}

// Unsigned integer made of digits only (O, checksum), at most kMaxProgramNumber.
inline long integer_value(ast::Line& line, const ast::Number& n, ast::NumberError too_large) {
  long result = 0;
  for (ast::Iterator c = n.begin; c != n.end; ++c) {
    const long digit = *c - '0';
    if (result > (kMaxProgramNumber - digit) / 10) {
      fail(line, too_large, n.begin);
      return 0;
    }
    result = result * 10 + digit;
  }
  return result;
}

// Fills `w` field by field (building a Word on the stack and copying it
// would read back the fields just written, a store-forwarding stall).
inline void set_word(ast::Line& line, ast::Iterator letter, const ast::Number& n, Word& w) {
  w.letter = upper(*letter);
  w.value = value(line, n);
  w.begin = offset(line, letter);
  w.number_begin = offset(line, n.begin);
  w.end = offset(line, n.end);
}

}  // namespace detail

// The attributes of the actions below: (letter position, number) for a
// word, N and O; the number for a checksum; the text for a comment. (In X3 an
// action's x3::_where begins where its subject's match ends.)

inline constexpr auto add_word = [](auto& ctx) {
  ast::Line& line = x3::_val(ctx);
  const auto& attribute = x3::_attr(ctx);
  const ast::Iterator letter = boost::fusion::at_c<0>(attribute);
  detail::set_word(line, letter, boost::fusion::at_c<1>(attribute),
                   line.block->words.emplace_back());
  detail::count_item(line, *letter, true);
};

inline constexpr auto add_line_number = [](auto& ctx) {
  ast::Line& line = x3::_val(ctx);
  const auto& attribute = x3::_attr(ctx);
  detail::set_word(line, boost::fusion::at_c<0>(attribute), boost::fusion::at_c<1>(attribute),
                   line.block->n.emplace());
  detail::count_item(line, 'N', false);
};

inline constexpr auto add_program_number = [](auto& ctx) {
  ast::Line& line = x3::_val(ctx);
  const auto& attribute = x3::_attr(ctx);
  line.block->program_number = detail::integer_value(line, boost::fusion::at_c<1>(attribute),
                                                     ast::NumberError::program_number_too_large);
  line.program_number_head = boost::fusion::at_c<0>(attribute);
  detail::count_item(line, 'O', false);
};

inline constexpr auto add_checksum = [](auto& ctx) {
  ast::Line& line = x3::_val(ctx);
  line.block->checksum = static_cast<int>(
      detail::integer_value(line, x3::_attr(ctx), ast::NumberError::checksum_too_large));
  detail::count_item(line, '*', false);
};

// '(' text ')' or ';' text: the attribute is the text, the match ends where
// x3::_where begins.
inline constexpr auto add_comment = [](auto& ctx) {
  ast::Line& line = x3::_val(ctx);
  const ast::Span& text = x3::_attr(ctx);
  const ast::Iterator head = text.begin() - 1;
  auto& comments = line.block->comments;
  // Comment strings of earlier lines are reused (resized by the caller at the end).
  if (line.n_comments == comments.size()) comments.emplace_back();
  Comment& c = comments[line.n_comments++];
  c.begin = detail::offset(line, head);
  c.end = detail::offset(line, x3::_where(ctx).begin());
  c.text.assign(text.begin(), text.end());
  detail::count_item(line, *head, true);
};

inline constexpr auto set_block_delete = [](auto& ctx) {
  ast::Line& line = x3::_val(ctx);
  line.block->block_delete = true;
  detail::count_item(line, '/', false);
};

inline constexpr auto set_percent = [](auto& ctx) {
  ast::Line& line = x3::_val(ctx);
  line.block->percent = true;
  detail::count_item(line, '%', false);
};

}  // namespace abbe::gcode::grammar
