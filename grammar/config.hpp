#pragma once
// Iterator and context types the grammar is instantiated for
// (src/gcode/gcode_grammar.cpp). Lines are parsed from a std::string_view
// without a skipper: blanks are significant for the byte offsets.
#include <boost/spirit/home/x3.hpp>

#include "grammar/ast.hpp"

namespace abbe::gcode::grammar {

namespace x3 = boost::spirit::x3;

using iterator_type = ast::Iterator;  // const char*
// The Line being filled travels in the context (x3::with<ast::line_tag>),
// so that the actions of nested rules (expressions) reach it.
using context_type = x3::context<ast::line_tag, ast::Line>;

}  // namespace abbe::gcode::grammar
