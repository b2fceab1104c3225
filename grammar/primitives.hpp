#pragma once
// Three small X3 primitive parsers the grammar is built from:
//   number_parser    the numbers of words, scanned once: while it matches
//                    `number` (or `digits`) of grammar/gcode.ebnf it collects
//                    what the conversion to double needs (ast::Number), so no
//                    second pass over the text is needed;
//   position_parser  matches nothing; its attribute is where it stands (the
//                    offset of a word letter for the semantic action);
//   blanks_parser    { " " | tab }, without an attribute (the most frequent
//                    parser of a line: after every item).
// Like every X3 parser they leave `first` unchanged when they fail.
#include <array>
#include <boost/spirit/home/x3.hpp>
#include <cstddef>
#include <cstdint>
#include <type_traits>
#include <utility>

#include "grammar/ast.hpp"

namespace abbe::gcode::grammar {

namespace x3 = boost::spirit::x3;

namespace detail {

// Appends the digits at `i` to n (mantissa: the first 19 digits only). The
// loop does the least per digit; the rare number with more than 19 digits
// (the mantissa wrapped) is redone with the cut-off.
inline void scan_digits(const char*& i, const char* last, ast::Number& n, bool fraction) {
  const char* const start = i;
  std::uint64_t mantissa = n.mantissa;
  for (; i != last && static_cast<unsigned char>(*i - '0') < 10; ++i)
    mantissa = mantissa * 10 + static_cast<std::uint64_t>(*i - '0');
  const auto count = static_cast<std::uint32_t>(i - start);
  if (n.digits + count > 19) {
    mantissa = n.mantissa;
    std::uint32_t digits = n.digits;
    for (const char* c = start; c != i && digits < 19; ++c, ++digits)
      mantissa = mantissa * 10 + static_cast<std::uint64_t>(*c - '0');
  }
  n.mantissa = mantissa;
  n.digits += count;
  if (fraction) n.fraction += count;
}

}  // namespace detail

// Real = true:  [ "+" | "-" ] , blanks , unsigned real
// Real = false: digits
template <bool Real>
struct number_parser : x3::parser<number_parser<Real>> {
  using attribute_type = ast::Number;
  static bool const has_attribute = true;

  template <typename It, typename Context, typename RContext, typename Attribute>
  bool parse(It& first, It const& last, Context const&, RContext&, Attribute& attribute) const {
    static_assert(std::is_same_v<It, const char*>, "the grammar parses const char* ranges");
    if constexpr (std::is_same_v<Attribute, ast::Number>) {
      return scan(first, last, attribute);  // straight into the action's attribute
    } else {
      ast::Number n;
      if (!scan(first, last, n)) return false;
      x3::traits::move_to(n, attribute);
      return true;
    }
  }

 private:
  // Matches at `first` and fills every field of n; n is garbage on failure.
  static bool scan(const char*& first, const char* last, ast::Number& n) {
    n.begin = first;
    n.mantissa = 0;
    n.digits = 0;
    n.fraction = 0;
    n.negative = false;
    n.point = false;
    const char* i = first;
    if constexpr (Real) {
      // Signs come in random order in a program: no branch on which one it is.
      if (i != last) {
        const bool minus = *i == '-';
        const bool sign = minus | (*i == '+');
        n.negative = minus;
        i += sign;
        const bool blank = i != last && (*i == ' ' || *i == '\t');
        if (sign & blank)
          while (i != last && (*i == ' ' || *i == '\t')) ++i;
      }
    }
    detail::scan_digits(i, last, n, false);
    if constexpr (Real) {
      if (i != last && *i == '.') {
        ++i;
        n.point = true;
        detail::scan_digits(i, last, n, true);
      }
    }
    if (n.digits == 0) return false;  // no digit: "", "+", "."
    n.end = i;
    first = i;
    return true;
  }
};

struct position_parser : x3::parser<position_parser> {
  using attribute_type = ast::Iterator;
  static bool const has_attribute = true;

  template <typename It, typename Context, typename RContext, typename Attribute>
  bool parse(It& first, It const&, Context const&, RContext&, Attribute& attribute) const {
    x3::traits::move_to(first, attribute);
    return true;
  }
};

struct blanks_parser : x3::parser<blanks_parser> {
  using attribute_type = x3::unused_type;
  static bool const has_attribute = false;

  template <typename It, typename Context, typename RContext, typename Attribute>
  bool parse(It& first, It const& last, Context const&, RContext&, Attribute&) const {
    while (first != last && (*first == ' ' || *first == '\t')) ++first;
    return true;
  }
};

// cold[p]: parses as p, in a function of its own that is never inlined.
// The rare items of a line (parameter settings, computed words, O-word
// lines) go through it, so that the compiler keeps the loop over the
// frequent ones (plain words, comments) in one function.
template <typename Subject>
struct cold_directive : x3::unary_parser<Subject, cold_directive<Subject>> {
  using base_type = x3::unary_parser<Subject, cold_directive<Subject>>;
  static bool const is_pass_through_unary = true;

  constexpr explicit cold_directive(Subject const& subject) : base_type(subject) {}

  template <typename It, typename Context, typename RContext, typename Attribute>
  bool parse(It& first, It const& last, Context const& context, RContext& rcontext,
             Attribute& attribute) const {
    // The iterators go by value: were their addresses passed on, the caller
    // could not keep its own in registers.
    const std::pair<bool, It> result = parse_apart(first, last, context, rcontext, attribute);
    if (result.first) first = result.second;
    return result.first;
  }

 private:
  template <typename It, typename Context, typename RContext, typename Attribute>
  BOOST_NOINLINE std::pair<bool, It> parse_apart(It first, It last, Context const& context,
                                                 RContext& rcontext, Attribute& attribute) const {
    const bool matched = this->subject.parse(first, last, context, rcontext, attribute);
    return {matched, first};
  }
};

struct cold_gen {
  template <typename Subject>
  constexpr cold_directive<typename x3::extension::as_parser<Subject>::value_type> operator[](
      Subject const& subject) const {
    return cold_directive<typename x3::extension::as_parser<Subject>::value_type>(
        x3::as_parser(subject));
  }
};

}  // namespace abbe::gcode::grammar

namespace abbe::gcode::grammar {

// One of a fixed list of case-insensitive ASCII keywords (operators and
// function names of expressions, O-word keywords); the longest one that
// matches wins (ELSEIF over ELSE, ** over *). Blanks may stand between its
// characters, as rs274ngc drops blanks ("else if", "end sub", "S I N"). Its attribute is the value
// listed with the keyword. A keyword made of letters must not run on into
// another letter when `whole_word` is set (O-word keywords).
template <typename T>
struct Keyword {
  const char* text;
  T value;
};

template <typename T, std::size_t N, bool WholeWord = false>
struct keyword_parser : x3::parser<keyword_parser<T, N, WholeWord>> {
  using attribute_type = T;
  static bool const has_attribute = true;

  const std::array<Keyword<T>, N>* table;

  explicit keyword_parser(const std::array<Keyword<T>, N>& t) : table(&t) {}

  template <typename It, typename Context, typename RContext, typename Attribute>
  bool parse(It& first, It const& last, Context const&, RContext&, Attribute& attribute) const {
    std::size_t best = 0;
    const Keyword<T>* found = nullptr;
    for (const Keyword<T>& k : *table) {
      // rs274ngc removes blanks before it reads a line: "else if" is "elseif".
      std::size_t n = 0;  // bytes of input matched
      std::size_t t = 0;  // characters of the keyword matched
      for (; k.text[t] != '\0'; ++t, ++n) {
        while (t > 0 && first + static_cast<std::ptrdiff_t>(n) != last &&
               (first[n] == ' ' || first[n] == '\t'))
          ++n;
        if (first + static_cast<std::ptrdiff_t>(n) == last) break;
        char c = first[n];
        if (c >= 'A' && c <= 'Z') c = static_cast<char>(c - 'A' + 'a');
        if (c != k.text[t]) break;
      }
      if (k.text[t] != '\0' || n <= best) continue;
      if constexpr (WholeWord) {
        const It after = first + static_cast<std::ptrdiff_t>(n);
        if (after != last && ((*after >= 'a' && *after <= 'z') || (*after >= 'A' && *after <= 'Z')))
          continue;
      }
      best = n;
      found = &k;
    }
    if (found == nullptr) return false;
    first += static_cast<std::ptrdiff_t>(best);
    x3::traits::move_to(found->value, attribute);
    return true;
  }
};

}  // namespace abbe::gcode::grammar
