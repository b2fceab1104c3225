#pragma once
// The Fanuc/Haas dialect, block by block (private to the library): what a
// block asks of the program flow (M98 / M99) and the block rewritten into
// its RS274/NGC equivalent for the interpreter. The rules, with the
// controller manuals' conventions they follow, are in docs/fanuc.md.
#include <optional>
#include <string_view>

#include "abbe/gcode/block.hpp"
#include "abbe/gcode/dialect.hpp"
#include "abbe/gcode/modal_groups.hpp"

namespace abbe::gcode::detail {

// M98 P<program> [L<count>] (or P<count><program> with 8 digits) and M99.
struct FanucFlow {
  std::optional<long> call;  // program number called by M98
  long repeats = 1;          // how many times (L, or the leading digits of P)
  bool ret = false;          // M99: end of a subprogram
  const Word* at = nullptr;  // the M98 / M99 word
};

// Throws InputError for what the flow cannot honour (M99 P, a bad P or L).
FanucFlow fanuc_flow(const Block& block, const BlockContext& ctx);

// Rewrites `block` into RS274/NGC in place (offsets kept, so a compensator
// still rewrites the right bytes): lengths without a decimal point scaled,
// dwell P/X in seconds, cycle repeats K as L, look-ahead and smoothing codes
// and M98/M99 removed, constructs abbe cannot honour refused by name.
// `inch`: the units in force before the block.
void adapt_fanuc_block(Block& block, std::string_view raw_line, bool inch, IntegerNumbers integers,
                       const BlockContext& ctx);

}  // namespace abbe::gcode::detail
