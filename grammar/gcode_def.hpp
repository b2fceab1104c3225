#pragma once
// Rule definitions of the G-code line grammar. grammar/gcode.ebnf documents
// exactly this language; keep both in step. Included only by
// src/gcode/gcode_grammar.cpp (the one instantiation).
#include <boost/spirit/home/x3.hpp>

#include "grammar/ast.hpp"
#include "grammar/ast_adapted.hpp"
#include "grammar/gcode.hpp"

namespace abbe::gcode::grammar {

namespace x3 = boost::spirit::x3;
using x3::attr;
using x3::char_;
using x3::lit;
using x3::raw;

// Lexical pieces (no attribute or an ignored one). Character classes are
// spelled out as explicit ASCII sets so that bytes >= 0x80 never reach a
// locale or an encoding assertion.
const auto blanks = *(lit(' ') | lit('\t'));
const auto digit = char_('0', '9');
const auto digits = +digit;
const auto unsigned_real = (digits >> -(lit('.') >> *digit)) | (lit('.') >> digits);
// A number must not run on into another digit, a second '.' or an exponent.
const auto number_end = !char_("0-9.eE");
// Letters of words abbe reads. A B C U V W (other axes), E, N and O are not
// here: N and O have their own rules, the rest is refused by the caller.
const auto word_letter = char_("DFGHIJKLMPQRSTXYZdfghijklmpqrstxyz");

const x3::rule<class word_class, ast::Item> word = "word";
const x3::rule<class line_number_class, ast::Item> line_number = "line number";
const x3::rule<class program_number_class, ast::Item> program_number = "program number";
const x3::rule<class checksum_class, ast::Item> checksum = "checksum";
const x3::rule<class paren_comment_class, ast::Item> paren_comment = "comment";
const x3::rule<class semicolon_comment_class, ast::Item> semicolon_comment = "comment";
const x3::rule<class block_delete_class, ast::Item> block_delete = "block delete";
const x3::rule<class percent_class, ast::Item> percent = "tape delimiter";
const x3::rule<class comment_class, ast::Item> comment = "comment";
const x3::rule<class item_class, ast::Item> item = "word or comment";
const line_type nc_line = "line";

// Every item swallows the blanks that follow it; raw[] keeps them out of its spans.
const auto word_def = raw[word_letter] >> blanks >> raw[-char_("+-") >> blanks >> unsigned_real] >>
                      number_end >> blanks;
const auto line_number_def = raw[char_("Nn")] >> blanks >> raw[digits] >> number_end >> blanks;
const auto program_number_def = raw[char_("Oo")] >> blanks >> raw[digits] >> number_end >> blanks;
const auto checksum_def = raw[lit('*')] >> raw[digits] >> number_end >> blanks;
const auto paren_comment_def = raw[lit('(')] >> raw[*~char_("()")] >> lit(')') >> blanks;
const auto semicolon_comment_def = raw[lit(';')] >> raw[*char_];
const auto block_delete_def = raw[lit('/')] >> attr(ast::Span()) >> blanks;
const auto percent_def = raw[lit('%')] >> attr(ast::Span()) >> blanks;

const auto comment_def = paren_comment | semicolon_comment;
const auto item_def = word | comment;

// Stores an item in the line. The line is filled by this action rather than by
// X3's container attribute propagation, which builds and appends temporary
// vectors in sequences: this way a line costs no allocation once its vector
// has grown.
const auto store = [](auto& ctx) { x3::_val(ctx).push_back(x3::_attr(ctx)); };

const auto percent_line = percent[store] >> -comment[store];
const auto program_line = program_number[store] >> -comment[store] >> -checksum[store];
const auto block = -line_number[store] >>
                   x3::repeat(std::size_t{0}, kMaxItemsPerBlock)[item[store]] >> -checksum[store];

// Every alternative is chosen by its first character and nothing can fail
// after an item has been stored, so no half-parsed item is ever left behind.
const auto nc_line_def = blanks >>
                         (percent_line | (-block_delete[store] >> (program_line | block)));

BOOST_SPIRIT_DEFINE(word, line_number, program_number, checksum, paren_comment, semicolon_comment,
                    block_delete, percent, comment, item, nc_line)

const line_type& line() { return nc_line; }

}  // namespace abbe::gcode::grammar
