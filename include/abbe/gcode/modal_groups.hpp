#pragma once
// Modal groups: sorts the words of one Block into G codes per modal group,
// M codes per group and the other letters, and refuses (InputError naming the
// word's file:line:col) two codes of one group, repeated letters, unknown
// codes and constructs abbe does not support. Group numbering follows the
// RS274/NGC (LinuxCNC) tables.
#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

#include "abbe/gcode/block.hpp"

namespace abbe::gcode {

// G codes are held as ten times their number (G91.1 -> 911), so that the
// decimal codes compare exactly.
constexpr int gcode_id(int whole, int tenth = 0) { return whole * 10 + tenth; }

enum class GGroup : std::uint8_t {
  non_modal,     // group 0: G4 G10 G28 G28.1 G30 G30.1 G52 G53 G92 G92.1 G92.2 G92.3
  motion,        // group 1: G0 G1 G2 G3 G73 G80 G81 G82 G83 G85 G89
  plane,         // group 2: G17 G18 G19
  distance,      // group 3: G90 G91
  arc_distance,  // group 4: G90.1 G91.1
  feed_mode,     // group 5: G93 G94 G95
  units,         // group 6: G20 G21
  cutter_comp,   // group 7: G40 G41 G41.1 G42 G42.1
  tool_length,   // group 8: G43 G43.1 G49
  retract,       // group 10: G98 G99
  coord_system,  // group 12: G54 .. G59
  path_control,  // group 13: G61 G61.1 G64
  spindle_mode,  // group 14: G97
  count
};

enum class MGroup : std::uint8_t {
  stopping,     // M0 M1 M2 M30 M60
  tool_change,  // M6 M61
  spindle,      // M3 M4 M5
  coolant,      // M7 M8 M9
  overrides,    // M48 M49 M50 M51 M52 M53 (carried: no geometry)
  modal_save,   // M70 M71 M72 M73 (save / invalidate / restore the modal state)
  count
};

struct CodeWord {
  int code;          // G: gcode_id; M: the integer number
  const Word* word;  // where it was written
};

// Error context of one block: formats InputErrors at a word's column.
struct BlockContext {
  const std::string& file;
  std::size_t line;
  std::string_view raw_line;
  [[noreturn]] void fail(const Word* at, const std::string& message) const;
};

// What classify_block found. Only the masks are initialised: an entry of
// the arrays is valid when its bit is set (a block is classified per line,
// so clearing some 500 bytes each time would show).
struct BlockCodes {
  std::uint32_t g_mask = 0;       // bit i: g[i] holds the code of GGroup i
  std::uint32_t m_mask = 0;       // bit i: m[i] holds the code of MGroup i
  std::uint32_t letter_mask = 0;  // bit letter_index(c): letters[that] is the word of letter c
  std::array<CodeWord, static_cast<std::size_t>(GGroup::count)> g;
  std::array<CodeWord, static_cast<std::size_t>(MGroup::count)> m;
  std::array<const Word*, 31> letters;

  // 'A'..'Z' -> 0..25, '^' (polar angle) -> 29, '@' (polar radius) -> 30.
  static constexpr unsigned letter_index(char letter) {
    return letter == '@' ? 30U : static_cast<unsigned>(letter - 'A');
  }

  // The code of a modal group, nullptr if the block has none.
  const CodeWord* group(GGroup which) const {
    const auto i = static_cast<std::size_t>(which);
    return (g_mask >> i) & 1U ? &g[i] : nullptr;
  }
  const CodeWord* group(MGroup which) const {
    const auto i = static_cast<std::size_t>(which);
    return (m_mask >> i) & 1U ? &m[i] : nullptr;
  }
  // The word of a letter (upper case, not G or M), nullptr if absent.
  const Word* word(char letter) const {
    const auto i = static_cast<std::size_t>(letter_index(letter));
    return (letter_mask >> i) & 1U ? letters[i] : nullptr;
  }
  bool has(char letter) const { return (letter_mask >> letter_index(letter)) & 1U; }
  // X, Y, Z, a rotary word A, B, C or a polar word @ ^ (rs274ngc: any axis
  // word makes a move).
  bool has_axis_word() const {
    constexpr std::uint32_t kAxes = (1U << ('X' - 'A')) | (1U << ('Y' - 'A')) |
                                    (1U << ('Z' - 'A')) | kRotaryLetters | kPolarLetters;
    return (letter_mask & kAxes) != 0;
  }
  static constexpr std::uint32_t kPolarLetters = (1U << 29) | (1U << 30);  // ^ @
  bool has_polar_word() const { return (letter_mask & kPolarLetters) != 0; }
  static constexpr std::uint32_t kRotaryLetters = 0x7U;  // A, B, C
  bool has_rotary_word() const { return (letter_mask & kRotaryLetters) != 0; }
};

// Sorts the block's words; throws InputError on conflicts or unsupported codes.
BlockCodes classify_block(const Block& block, const BlockContext& where);

// "G91.1", "G0", "M30": the code as a programmer writes it.
std::string gcode_name(int id);

}  // namespace abbe::gcode
