// Turns the AST of grammar/ into abbe::gcode::Block and reads programs line
// by line. The grammar accepts the longest valid prefix of a line; anything
// left over is explained by parse_diagnosis.cpp.
#include "abbe/gcode/parser.hpp"

#include <fmt/format.h>

#include <charconv>
#include <cmath>
#include <cstdint>
#include <limits>

#include "abbe/io/input_error.hpp"
#include "grammar/ast.hpp"
#include "grammar/gcode.hpp"
#include "parse_diagnosis.hpp"

namespace abbe::gcode {

namespace {

// Numbers longer than this (digits and '.') are refused: no CAM post emits
// them and they can only be garbage.
constexpr std::size_t kMaxNumberChars = 64;

char upper(char c) { return (c >= 'a' && c <= 'z') ? static_cast<char>(c - 'a' + 'A') : c; }

struct LineContext {
  std::string_view line;
  std::size_t line_number;
  const std::string& file;

  std::uint32_t offset(ast::Iterator it) const {
    return static_cast<std::uint32_t>(it - line.data());
  }
  InputError error(ast::Iterator at, const std::string& message) const {
    return detail::line_error(line, line_number, file, offset(at), message);
  }
};

// The value of a number as the grammar matched it: optional sign, blanks,
// digits with an optional '.'.
double number_value(const ast::Span& number, const LineContext& ctx) {
  // Fast path (Clinger): an integer mantissa below 2^53 and a power of ten up
  // to 1e22 are exact doubles, so one division rounds correctly and gives the
  // same double as from_chars. Typical CAM numbers (X-123.4567) take it.
  static constexpr double kPow10[] = {1e0,  1e1,  1e2,  1e3,  1e4,  1e5,  1e6,  1e7,
                                      1e8,  1e9,  1e10, 1e11, 1e12, 1e13, 1e14, 1e15,
                                      1e16, 1e17, 1e18, 1e19, 1e20, 1e21, 1e22};
  constexpr std::uint64_t kMaxExactMantissa = std::uint64_t{1} << 53;
  bool negative = false;
  std::uint64_t mantissa = 0;
  std::size_t n_digits = 0;
  std::size_t n_fraction = 0;
  bool in_fraction = false;
  for (char c : number) {
    if (c == '-') {
      negative = true;
    } else if (c == '.') {
      in_fraction = true;
    } else if (c >= '0' && c <= '9') {
      if (n_digits < 19) mantissa = mantissa * 10 + static_cast<std::uint64_t>(c - '0');
      ++n_digits;
      if (in_fraction) ++n_fraction;
    }
  }
  const std::size_t significant = n_digits + (in_fraction ? 1 : 0);
  if (significant > kMaxNumberChars)
    throw ctx.error(number.begin(), "number is too long (more than 64 characters)");
  if (n_digits <= 19 && mantissa <= kMaxExactMantissa && n_fraction <= 22) {
    const double magnitude = static_cast<double>(mantissa) / kPow10[n_fraction];
    return negative ? -magnitude : magnitude;
  }
  // General case: correctly rounded conversion of the text without blanks and '+'.
  char buffer[kMaxNumberChars + 2];
  std::size_t n = 0;
  for (char c : number)
    if (c != ' ' && c != '\t' && c != '+') buffer[n++] = c;
  double value = 0.0;
  const auto [end, ec] = std::from_chars(buffer, buffer + n, value);
  if (ec != std::errc() || end != buffer + n || !std::isfinite(value))
    throw ctx.error(number.begin(), "number is out of range");
  return value;
}

// Unsigned integer made of digits only (N, O, checksum), at most `max`.
long integer_value(const ast::Span& digits, long max, const char* what, const LineContext& ctx) {
  long value = 0;
  for (char c : digits) {
    const long digit = c - '0';
    if (value > (max - digit) / 10)
      throw ctx.error(digits.begin(), fmt::format("{} is too large (at most {})", what, max));
    value = value * 10 + digit;
  }
  return value;
}

Word make_word(char letter, const ast::Item& item, const LineContext& ctx) {
  Word w;
  w.letter = letter;
  w.value = number_value(item.body, ctx);
  w.begin = ctx.offset(item.head.begin());
  w.number_begin = ctx.offset(item.body.begin());
  w.end = ctx.offset(item.body.end());
  return w;
}

void reset(Block& block, std::size_t line_number) {
  block.line = line_number;
  block.block_delete = false;
  block.percent = false;
  block.program_number.reset();
  block.n.reset();
  block.words.clear();
  block.checksum.reset();
}

}  // namespace

void parse_line(std::string_view line, std::size_t line_number, const std::string& file,
                Block& block) {
  if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
  const LineContext ctx{line, line_number, file};
  if (line.size() > std::numeric_limits<std::uint32_t>::max())
    throw detail::line_error(line, line_number, file, 0, "line is longer than 4 GiB");

  // The AST is scratch space; keeping it per thread avoids an allocation per line.
  thread_local ast::Line items;
  items.clear();
  ast::Iterator first = line.data();
  const ast::Iterator last = line.data() + line.size();
  boost::spirit::x3::parse(first, last, grammar::line(), items);
  if (first != last)
    throw detail::explain_parse_stop(line, static_cast<std::size_t>(first - line.data()), items,
                                     line_number, file);

  reset(block, line_number);
  std::size_t n_comments = 0;
  for (const auto& item : items)
    if (*item.head.begin() == '(' || *item.head.begin() == ';') ++n_comments;
  // Resize rather than clear: the strings of kept comments reuse their capacity.
  block.comments.resize(n_comments);
  std::size_t comment_index = 0;

  for (const auto& item : items) {
    const char head = upper(*item.head.begin());
    switch (head) {
      case '/':
        block.block_delete = true;
        break;
      case '%':
        block.percent = true;
        break;
      case 'O':
        block.program_number = integer_value(item.body, 999'999'999L, "program number", ctx);
        break;
      case 'N':
        block.n = make_word('N', item, ctx);
        break;
      case '*':
        block.checksum = static_cast<int>(integer_value(item.body, 999'999'999L, "checksum", ctx));
        break;
      case '(':
      case ';': {
        Comment& c = block.comments[comment_index++];
        c.begin = ctx.offset(item.head.begin());
        c.end = ctx.offset(item.body.end()) + (head == '(' ? 1U : 0U);
        c.text.assign(item.body.begin(), item.body.end());
        break;
      }
      default:
        block.words.push_back(make_word(head, item, ctx));
    }
  }
}

Block parse_line(std::string_view line, std::size_t line_number, const std::string& file) {
  Block block;
  parse_line(line, line_number, file, block);
  return block;
}

BlockReader::BlockReader(std::istream& in, std::string file) : in_(in), file_(std::move(file)) {}

bool BlockReader::next(Block& block) {
  if (!std::getline(in_, line_)) {
    if (in_.bad())
      throw InputError(SourceLocation{file_, line_number_ + 1, 0, "", ""}, "read error");
    return false;
  }
  ++line_number_;
  if (line_number_ == 1 && line_.compare(0, 3, "\xEF\xBB\xBF") == 0) {
    // A UTF-8 byte order mark (some Windows editors write one) is not part of
    // the program: drop it, offsets then refer to the line without it.
    line_.erase(0, 3);
    byte_order_mark_ = true;
  }
  line_ending_ = in_.eof() ? "" : "\n";
  if (!line_.empty() && line_.back() == '\r') {
    line_.pop_back();
    line_ending_ = *line_ending_ != '\0' ? "\r\n" : "\r";
  }
  parse_line(line_, line_number_, file_, block);
  return true;
}

}  // namespace abbe::gcode
