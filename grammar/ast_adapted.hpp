#pragma once
// Fusion adaptation of the AST so that X3 sequences fill it directly.
#include <boost/fusion/include/adapt_struct.hpp>

#include "grammar/ast.hpp"

BOOST_FUSION_ADAPT_STRUCT(abbe::gcode::ast::Item, head, body)
