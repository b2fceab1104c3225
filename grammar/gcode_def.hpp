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
// (rotary axes) and E are read: the interpreter decides on them.
const auto word_letter = char_("ABCDEFGHIJKLMPQRSTXYZabcdefghijklmpqrstxyz");

// Every item swallows the blanks that follow it; the action sees only the
// item itself. The optional items N, O and '*' are looked at (&) before
// their attributes are built: most lines have none of them.
const auto word =
    (position >> omit[word_letter] >> blanks >> number >> number_end)[add_word] >> blanks;
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
const auto item = word | comment;

const auto percent_line = percent >> -comment;
const auto program_line = program_number >> -comment >> -checksum;
const auto block = -line_number >> x3::repeat(std::size_t{0}, kMaxItemsPerBlock)[item] >> -checksum;

// Every alternative is chosen by its first character and nothing can fail
// after an item has been stored, so no half-parsed item is ever left behind.
const line_type nc_line = "line";
const auto nc_line_def = blanks >> (percent_line | (-block_delete >> (program_line | block)));

BOOST_SPIRIT_DEFINE(nc_line)

const line_type& line() { return nc_line; }

}  // namespace abbe::gcode::grammar
