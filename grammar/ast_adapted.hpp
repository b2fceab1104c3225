#pragma once
// Fusion support for the AST. The semantic actions (grammar/line_actions.hpp)
// receive the attributes of X3 sequences as Fusion sequences, e.g. (letter
// position, number) for a word; no AST struct needs adapting because the actions
// write the Block directly.
#include <boost/fusion/include/at_c.hpp>
#include <boost/fusion/include/deque.hpp>

#include "grammar/ast.hpp"
