#pragma once
// Semantic actions of expressions, parameters, parameter settings and
// O-words (grammar/gcode_def.hpp): they append postfix code to the Block of
// the ast::Line carried in the context (ast::line_tag) and record which
// piece of code belongs to which word, setting or O-word argument. The code
// of a construct is complete once its action runs; a construct that fails
// half-way makes the whole line fail (every alternative is chosen by its
// first character), so stray code is never executed.
#include <boost/fusion/include/at_c.hpp>
#include <boost/spirit/home/x3.hpp>
#include <string>

#include "abbe/gcode/expression.hpp"
#include "grammar/ast.hpp"
#include "grammar/line_actions.hpp"

namespace abbe::gcode::grammar {

namespace x3 = boost::spirit::x3;

namespace detail {

template <typename Context>
ast::Line& line_of(const Context& ctx) {
  return x3::get<ast::line_tag>(ctx);
}

inline std::uint32_t code_size(const ast::Line& line) {
  return static_cast<std::uint32_t>(line.block->code.size());
}

inline void push(ast::Line& line, ExprOp op, ast::Iterator at, std::uint32_t arg = 0,
                 double value = 0.0) {
  line.block->code.push_back(ExprCode{op, offset(line, at), arg, value});
  if (line.expression_reach == nullptr || at > line.expression_reach) line.expression_reach = at;
}

// A parameter name as rs274ngc compares it: lower case, blanks removed.
inline std::uint32_t add_name(ast::Line& line, const ast::Span& text) {
  std::string name;
  for (char c : text) {
    if (c == ' ' || c == '\t') continue;
    name += (c >= 'A' && c <= 'Z') ? static_cast<char>(c - 'A' + 'a') : c;
  }
  line.block->names.push_back(std::move(name));
  return static_cast<std::uint32_t>(line.block->names.size() - 1);
}

inline CodeRange take_code(ast::Line& line) {
  const CodeRange range{line.code_mark, code_size(line)};
  line.code_mark = range.end;
  return range;
}

}  // namespace detail

// A number as an operand: (number).
inline constexpr auto push_number = [](auto& ctx) {
  ast::Line& line = detail::line_of(ctx);
  const ast::Number& n = x3::_attr(ctx);
  const double v = detail::value(line, n);
  detail::push(line, ExprOp::number, n.begin, 0, v);
};

// (position, operator) after the right operand: the operator's code.
inline constexpr auto push_operator = [](auto& ctx) {
  ast::Line& line = detail::line_of(ctx);
  const auto& attribute = x3::_attr(ctx);
  detail::push(line, boost::fusion::at_c<1>(attribute), boost::fusion::at_c<0>(attribute));
};

// (position) of a '-' after its operand.
inline constexpr auto push_negate = [](auto& ctx) {
  ast::Line& line = detail::line_of(ctx);
  detail::push(line, ExprOp::negate, x3::_attr(ctx));
};

// (position) of a '#' after its index.
inline constexpr auto push_parameter = [](auto& ctx) {
  ast::Line& line = detail::line_of(ctx);
  detail::push(line, ExprOp::parameter, x3::_attr(ctx));
};

// (position, name) of #<name>.
inline constexpr auto push_named = [](auto& ctx) {
  ast::Line& line = detail::line_of(ctx);
  const auto& attribute = x3::_attr(ctx);
  const std::uint32_t name = detail::add_name(line, boost::fusion::at_c<1>(attribute));
  detail::push(line, ExprOp::named, boost::fusion::at_c<0>(attribute), name);
};

// (position, name) of EXISTS[#<name>].
inline constexpr auto push_exists = [](auto& ctx) {
  ast::Line& line = detail::line_of(ctx);
  const auto& attribute = x3::_attr(ctx);
  const std::uint32_t name = detail::add_name(line, boost::fusion::at_c<1>(attribute));
  detail::push(line, ExprOp::exists, boost::fusion::at_c<0>(attribute), name);
};

// (position, letter position) of a word whose value is an expression.
inline constexpr auto add_expression_word = [](auto& ctx) {
  ast::Line& line = detail::line_of(ctx);
  const ast::Iterator letter = x3::_attr(ctx);
  Block& block = *line.block;
  Word& w = block.words.emplace_back();
  w.letter = detail::upper(*letter);
  w.value = 0.0;
  w.begin = detail::offset(line, letter);
  w.number_begin = w.begin + 1;
  w.end = detail::offset(line, x3::_where(ctx).begin());
  block.word_expressions.push_back(
      WordExpression{static_cast<std::uint32_t>(block.words.size() - 1), detail::take_code(line)});
  detail::count_item(line, *letter, true);
};

// (name) of the #<name> a setting assigns.
inline constexpr auto set_target_name = [](auto& ctx) {
  ast::Line& line = detail::line_of(ctx);
  line.target_name = static_cast<std::int32_t>(detail::add_name(line, x3::_attr(ctx)));
};

// At the '=' of a setting: the index code (if any) ends here.
inline constexpr auto mark_target_end = [](auto& ctx) {
  ast::Line& line = detail::line_of(ctx);
  line.target_end = detail::code_size(line);
};

// (position of '#') after the value of a setting.
inline constexpr auto add_setting = [](auto& ctx) {
  ast::Line& line = detail::line_of(ctx);
  const ast::Iterator hash = x3::_attr(ctx);
  ParameterSetting s;
  s.name = line.target_name;
  s.index = CodeRange{line.code_mark, line.target_end};
  s.value = CodeRange{line.target_end, detail::code_size(line)};
  s.column = detail::offset(line, hash);
  line.code_mark = s.value.end;
  line.target_name = -1;
  line.block->settings.push_back(s);
  detail::count_item(line, '#', true);
};

// (position of 'o', label, keyword) of an O-word line.
inline constexpr auto set_o_word = [](auto& ctx) {
  ast::Line& line = detail::line_of(ctx);
  const auto& attribute = x3::_attr(ctx);
  OWord& o = line.block->o;
  o.column = detail::offset(line, boost::fusion::at_c<0>(attribute));
  const ast::Span& label = boost::fusion::at_c<1>(attribute);
  o.label.clear();
  const bool numbered =
      label.begin() != label.end() && *label.begin() >= '0' && *label.begin() <= '9';
  for (char c : label) {
    if (c == ' ' || c == '\t') continue;
    if (numbered && c == '0' && o.label.empty()) continue;  // o0100 is o100
    o.label += (c >= 'A' && c <= 'Z') ? static_cast<char>(c - 'A' + 'a') : c;
  }
  if (numbered && o.label.empty()) o.label = "0";
  o.keyword_column = detail::offset(line, boost::fusion::at_c<2>(attribute));
  o.keyword = boost::fusion::at_c<3>(attribute);
  o.args.clear();
  detail::count_item(line, 'O', false);
};

// After one [...] argument of an O-word.
inline constexpr auto add_o_argument = [](auto& ctx) {
  ast::Line& line = detail::line_of(ctx);
  line.block->o.args.push_back(detail::take_code(line));
};

}  // namespace abbe::gcode::grammar
