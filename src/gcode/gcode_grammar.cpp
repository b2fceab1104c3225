// The one translation unit that instantiates the X3 grammar (X3 compiles
// slowly; everything else includes only grammar/gcode.hpp).
#include "grammar/config.hpp"
#include "grammar/gcode_def.hpp"

namespace abbe::gcode::grammar {

BOOST_SPIRIT_INSTANTIATE(line_type, iterator_type, context_type)

}  // namespace abbe::gcode::grammar
