#pragma once
// Rule definitions of the G-code line grammar. grammar/gcode.ebnf documents
// exactly this language; keep both in step. Included only by
// src/gcode/gcode_grammar.cpp (the one instantiation).
//
// Only the line is an X3 rule; its parts are plain parser expressions so
// that the compiler inlines the whole line parser. Semantic actions
// (grammar/line_actions.hpp) store each item into the Block as soon as it
// has matched; numbers are scanned once (grammar/primitives.hpp).
#include <boost/spirit/home/x3.hpp>

#include "grammar/ast.hpp"
#include "grammar/ast_adapted.hpp"
#include "grammar/expression_actions.hpp"
#include "grammar/gcode.hpp"
#include "grammar/line_actions.hpp"
#include "grammar/primitives.hpp"

namespace abbe::gcode::grammar {

namespace x3 = boost::spirit::x3;
using x3::char_;
using x3::lit;
using x3::omit;
using x3::raw;

// Lexical pieces. Character classes are spelled out as explicit ASCII sets
// so that bytes >= 0x80 never reach a locale or an encoding assertion.
const auto blanks = blanks_parser{};         // { " " | tab }
const auto position = position_parser{};     // where a word letter is
const auto digits = number_parser<false>{};  // digit , { digit }
const auto number = number_parser<true>{};   // [ "+" | "-" ] , blanks , unsigned real
// A number must not run on into another digit, a second '.' or an exponent.
const auto number_end = !char_("0-9.eE");
// Letters of words abbe reads. U V W (other axes), N and O are not here: N
// and O have their own rules, the rest is refused by the caller. A B C
// (rotary axes) and E are read: the interpreter decides on them. '@' and
// '^' are rs274ngc's polar radius and angle (the interpreter turns them into X, Y).
const auto word_letter = char_("ABCDEFGHIJKLMPQRSTXYZabcdefghijklmpqrstxyz@^");

// Expressions (rs274ngc's read_real_value and read_real_expression).
// Operators by precedence, each level left-associative.
inline const std::array<Keyword<ExprOp>, 3> kLogicalOps = {
    {{"and", ExprOp::and_}, {"or", ExprOp::or_}, {"xor", ExprOp::xor_}}};
inline const std::array<Keyword<ExprOp>, 6> kRelationalOps = {{{"eq", ExprOp::eq},
                                                               {"ne", ExprOp::ne},
                                                               {"gt", ExprOp::gt},
                                                               {"ge", ExprOp::ge},
                                                               {"lt", ExprOp::lt},
                                                               {"le", ExprOp::le}}};
inline const std::array<Keyword<ExprOp>, 2> kAdditiveOps = {
    {{"+", ExprOp::plus}, {"-", ExprOp::minus}}};
inline const std::array<Keyword<ExprOp>, 4> kMultiplicativeOps = {
    {{"*", ExprOp::times}, {"**", ExprOp::power}, {"/", ExprOp::divide}, {"mod", ExprOp::modulo}}};
inline const std::array<Keyword<ExprOp>, 12> kFunctions = {{{"abs", ExprOp::abs},
                                                            {"acos", ExprOp::acos},
                                                            {"asin", ExprOp::asin},
                                                            {"cos", ExprOp::cos},
                                                            {"exp", ExprOp::exp},
                                                            {"fix", ExprOp::fix},
                                                            {"fup", ExprOp::fup},
                                                            {"ln", ExprOp::ln},
                                                            {"round", ExprOp::round},
                                                            {"sin", ExprOp::sin},
                                                            {"sqrt", ExprOp::sqrt},
                                                            {"tan", ExprOp::tan}}};
inline const std::array<Keyword<ExprOp>, 1> kAtan = {{{"atan", ExprOp::atan}}};
inline const std::array<Keyword<ExprOp>, 1> kExists = {{{"exists", ExprOp::exists}}};
inline const std::array<Keyword<OKeyword>, 15> kOKeywords = {{{"sub", OKeyword::sub},
                                                              {"endsub", OKeyword::endsub},
                                                              {"call", OKeyword::call},
                                                              {"return", OKeyword::return_},
                                                              {"do", OKeyword::do_},
                                                              {"while", OKeyword::while_},
                                                              {"endwhile", OKeyword::endwhile},
                                                              {"if", OKeyword::if_},
                                                              {"elseif", OKeyword::elseif},
                                                              {"else", OKeyword::else_},
                                                              {"endif", OKeyword::endif},
                                                              {"break", OKeyword::break_},
                                                              {"continue", OKeyword::continue_},
                                                              {"repeat", OKeyword::repeat},
                                                              {"endrepeat", OKeyword::endrepeat}}};

const auto logical_op = keyword_parser<ExprOp, 3>(kLogicalOps);
const auto relational_op = keyword_parser<ExprOp, 6>(kRelationalOps);
const auto additive_op = keyword_parser<ExprOp, 2>(kAdditiveOps);
// '*' only where '**' (the tighter power operator) does not match.
const auto multiplicative_op = keyword_parser<ExprOp, 4>(kMultiplicativeOps);
const auto power_op = lit("**") >> x3::attr(ExprOp::power);
const auto function_name = keyword_parser<ExprOp, 12>(kFunctions);
const auto atan_name = keyword_parser<ExprOp, 1>(kAtan);
const auto exists_name = keyword_parser<ExprOp, 1>(kExists);
const auto o_keyword = keyword_parser<OKeyword, 15, true>(kOKeywords);

// #<name>: blanks are not part of the name.
struct name_text_class;
struct o_label_class;
const x3::rule<name_text_class, ast::Span> name_text = "name";
// Any printable character but '>' (rs274ngc: #<_hal[pin.name]>, #<_move:x>, o<probe-hole>).
const auto name_text_def = raw[+(char_("\x20-\x3d") | char_("\x3f-\x7e") | char_('\t'))];
const auto name = lit('<') >> name_text >> lit('>');
const x3::rule<o_label_class, ast::Span> o_label = "O-word label";
const auto o_label_def = raw[digits] | (lit('<') >> name_text >> lit('>'));
BOOST_SPIRIT_DEFINE(name_text, o_label)

struct bracketed_class;
struct value_class;
struct logical_class;
const x3::rule<bracketed_class> bracketed = "expression";  // "[" logical "]"
const x3::rule<value_class> real_value = "value";
const x3::rule<logical_class> logical = "expression";

const auto power_level = real_value >>
                         *((position >> power_op >> blanks >> real_value)[push_operator]);
const auto multiplicative_level = power_level >> *((position >> multiplicative_op >> blanks >>
                                                    power_level)[push_operator]);
const auto additive_level = multiplicative_level >> *((position >> additive_op >> blanks >>
                                                       multiplicative_level)[push_operator]);
const auto relational_level = additive_level >> *((position >> relational_op >> blanks >>
                                                   additive_level)[push_operator]);
const auto logical_def = relational_level >>
                         *((position >> logical_op >> blanks >> relational_level)[push_operator]);

const auto bracketed_def = lit('[') >> blanks >> logical >> lit(']') >> blanks;

const auto parameter = (position >> lit('#') >> blanks >> name)[push_named] >> blanks |
                       (position >> lit('#') >> blanks >> real_value)[push_parameter];
const auto function = (position >> atan_name >> blanks >> bracketed >> lit('/') >> blanks >>
                       bracketed)[push_operator] |
                      (position >> omit[exists_name] >> blanks >> lit('[') >> blanks >> lit('#') >>
                       blanks >> name >> blanks >> lit(']'))[push_exists] >>
                          blanks |
                      (position >> function_name >> blanks >> bracketed)[push_operator];
const auto real_value_def = bracketed | parameter |
                            (number >> !char_("0-9."))[push_number] >> blanks |
                            (position >> lit('-') >> blanks >> real_value)[push_negate] |
                            lit('+') >> blanks >> real_value | function;

BOOST_SPIRIT_DEFINE(bracketed, real_value, logical)

// Every item swallows the blanks that follow it; the action sees only the
// item itself. The optional items N, O and '*' are looked at (&) before
// their attributes are built: most lines have none of them.
// A word's value is a number (the fast path, tried first) or, in the
// LinuxCNC dialect, a parameter or an expression: X#1, X[#1+2], X-#<a>,
// XSIN[30] (rs274ngc's read_real_value).
const auto plain_word =
    (position >> omit[word_letter] >> blanks >> number >> number_end)[add_word] >> blanks;
// A value that begins like a number is a plain number or wrong (X1e5, X1.2.3
// are explained as bad numbers): only other values are read as expressions.
const auto expression_word =
    (position >> omit[word_letter] >> blanks >> !number >> real_value)[add_expression_word];
// #n = value, #<name> = value (n itself may be a value: #[#1+1] = 2).
const auto setting_target = omit[name[set_target_name]] >> blanks | real_value;
const auto setting = (position >> lit('#') >> blanks >> setting_target >>
                      lit('=')[mark_target_end] >> blanks >> real_value)[add_setting];
const auto line_number =
    &char_("Nn") >>
    (position >> omit[char_("Nn")] >> blanks >> digits >> number_end)[add_line_number] >> blanks;
const auto program_number =
    &char_("Oo") >>
    (position >> omit[char_("Oo")] >> blanks >> digits >> number_end)[add_program_number] >> blanks;
const auto checksum = &lit('*') >> (lit('*') >> digits >> number_end)[add_checksum] >> blanks;
const auto paren_comment = (lit('(') >> raw[*~char_("()")] >> lit(')'))[add_comment] >> blanks;
const auto semicolon_comment = (lit(';') >> raw[*char_])[add_comment];
const auto block_delete = lit('/')[set_block_delete] >> blanks;
const auto percent = lit('%')[set_percent] >> blanks;

const auto comment = paren_comment | semicolon_comment;
// The alternatives begin with different characters (a word letter, '(' or
// ';', '#'), so their order does not change what a line means; it is the
// order of their cost on a CAM line, which ends after its last word or
// comment: the plain word first, the expression word (which looks for a
// word letter again) last. (Measured: 1.9 % fewer instructions than
// "word | setting | comment" for `abbe interpret` on the 1 M-block program.)
// The setting and the expression word go through cold[...] behind a look-ahead
// of their first character (a '#' or a word letter): a CAM line has
// neither, and the loop over its words stays small enough to be inlined
// into the line rule (docs/performance.md, "fifth run").
const auto cold = cold_gen{};
const auto item =
    plain_word | comment |
    &char_("#ABCDEFGHIJKLMPQRSTXYZabcdefghijklmpqrstxyz@^") >> cold[setting | expression_word];

// O-word control flow: o100 sub, o<name> call [1] [2], o101 if [#1 GT 0], ...
const auto o_line = &char_("Oo") >> (position >> omit[char_("Oo")] >> blanks >> o_label >> blanks >>
                                     position >> o_keyword)[set_o_word] >>
                    blanks >> *(bracketed[add_o_argument]) >> *comment;

const auto percent_line = percent >> -comment;
const auto program_line = program_number >> -comment >> -checksum;
const auto block = -line_number >> x3::repeat(std::size_t{0}, kMaxItemsPerBlock)[item] >> -checksum;

// Every alternative is chosen by its first character and nothing can fail
// after an item has been stored, so no half-parsed item is ever left behind.
const line_type nc_line = "line";
const auto nc_line_def = blanks >>
                         (&lit('%') >> cold[percent_line] |
                          (-block_delete >> (&char_("Oo") >> cold[o_line | program_line] | block)));

BOOST_SPIRIT_DEFINE(nc_line)

const line_type& line() { return nc_line; }

}  // namespace abbe::gcode::grammar
