#pragma once
// Iterator and context types the grammar is instantiated for
// (src/gcode/gcode_grammar.cpp). Lines are parsed from a std::string_view
// without a skipper: blanks are significant for the byte offsets.
#include <boost/spirit/home/x3.hpp>

#include "grammar/ast.hpp"

namespace abbe::gcode::grammar {

namespace x3 = boost::spirit::x3;

using iterator_type = ast::Iterator;  // const char*
using context_type = x3::unused_type;

}  // namespace abbe::gcode::grammar
