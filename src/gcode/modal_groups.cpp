#include "abbe/gcode/modal_groups.hpp"

#include <fmt/format.h>

#include <cmath>
#include <cstdint>

#include "abbe/io/input_error.hpp"
#include "hot.hpp"

namespace abbe::gcode {

namespace {

struct GInfo {
  std::optional<GGroup> group;    // empty: refused
  const char* refusal = nullptr;  // what the construct is, for the error message
};

GInfo g_info(int id) {
  switch (id) {
    case gcode_id(4):
    case gcode_id(10):
    case gcode_id(28):
    case gcode_id(28, 1):
    case gcode_id(30):
    case gcode_id(30, 1):
    case gcode_id(52):
    case gcode_id(53):
    case gcode_id(92):
    case gcode_id(92, 1):
    case gcode_id(92, 2):
    case gcode_id(92, 3):
      return {GGroup::non_modal};
    case gcode_id(0):
    case gcode_id(1):
    case gcode_id(2):
    case gcode_id(3):
    case gcode_id(73):
    case gcode_id(80):
    case gcode_id(81):
    case gcode_id(82):
    case gcode_id(83):
    case gcode_id(74):
    case gcode_id(84):
    case gcode_id(85):
    case gcode_id(86):
    case gcode_id(87):
    case gcode_id(89):
      return {GGroup::motion};
    case gcode_id(17):
    case gcode_id(18):
    case gcode_id(19):
      return {GGroup::plane};
    case gcode_id(90):
    case gcode_id(91):
      return {GGroup::distance};
    case gcode_id(90, 1):
    case gcode_id(91, 1):
      return {GGroup::arc_distance};
    case gcode_id(93):
    case gcode_id(94):
    case gcode_id(95):
      return {GGroup::feed_mode};
    case gcode_id(20):
    case gcode_id(21):
      return {GGroup::units};
    case gcode_id(40):
    case gcode_id(41):
    case gcode_id(41, 1):
    case gcode_id(42):
    case gcode_id(42, 1):
      return {GGroup::cutter_comp};
    case gcode_id(43):
    case gcode_id(43, 1):
    case gcode_id(43, 2):
    case gcode_id(49):
      return {GGroup::tool_length};
    case gcode_id(98):
    case gcode_id(99):
      return {GGroup::retract};
    case gcode_id(54):
    case gcode_id(55):
    case gcode_id(56):
    case gcode_id(57):
    case gcode_id(58):
    case gcode_id(59):
      return {GGroup::coord_system};
    case gcode_id(61):
    case gcode_id(61, 1):
    case gcode_id(64):
      return {GGroup::path_control};
    case gcode_id(97):
      return {GGroup::spindle_mode};
    // Known constructs abbe refuses, with their names.
    case gcode_id(5):
    case gcode_id(5, 1):
    case gcode_id(5, 2):
    case gcode_id(5, 3):
      return {std::nullopt, "spline / NURBS motion"};
    case gcode_id(7):
    case gcode_id(8):
      return {std::nullopt, "lathe diameter/radius mode"};
    case gcode_id(15):
    case gcode_id(16):
      return {std::nullopt, "polar coordinate mode"};
    case gcode_id(17, 1):
    case gcode_id(18, 1):
    case gcode_id(19, 1):
      return {std::nullopt, "U, V, W plane selection"};
    case gcode_id(33):
    case gcode_id(33, 1):
    case gcode_id(76):
      return {std::nullopt, "spindle-synchronised motion (threading)"};
    case gcode_id(38, 2):
    case gcode_id(38, 3):
    case gcode_id(38, 4):
    case gcode_id(38, 5):
      return {std::nullopt, "probing"};
    case gcode_id(59, 1):
    case gcode_id(59, 2):
    case gcode_id(59, 3):
      return {std::nullopt, "coordinate system beyond G59"};
    case gcode_id(68):
    case gcode_id(69):
      return {std::nullopt, "coordinate system rotation"};
    case gcode_id(70):
    case gcode_id(71):
    case gcode_id(71, 1):
    case gcode_id(71, 2):
    case gcode_id(72):
    case gcode_id(72, 1):
    case gcode_id(72, 2):
      return {std::nullopt, "lathe cycle"};
    case gcode_id(88):
      return {std::nullopt, "boring cycle with a manual retract"};
    case gcode_id(96):
      return {std::nullopt, "constant surface speed"};
    default:
      return {std::nullopt, nullptr};
  }
}

std::optional<MGroup> m_group(int number) {
  switch (number) {
    case 0:
    case 1:
    case 2:
    case 30:
    case 60:
      return MGroup::stopping;
    case 6:
    case 61:
      return MGroup::tool_change;
    case 3:
    case 4:
    case 5:
      return MGroup::spindle;
    case 7:
    case 8:
    case 9:
      return MGroup::coolant;
    case 48:
    case 49:
    case 50:
    case 51:
    case 52:
    case 53:
      return MGroup::overrides;
    case 70:
    case 71:
    case 72:
    case 73:
      return MGroup::modal_save;
    default:
      return std::nullopt;
  }
}

// std::round for 0 <= v < 2^52 without a library call.
double round_half_up(double v) { return static_cast<double>(static_cast<std::int64_t>(v + 0.5)); }

std::string format_number(double v) {
  std::string s = fmt::format("{:.4f}", v);
  while (!s.empty() && s.back() == '0') s.pop_back();
  if (!s.empty() && s.back() == '.') s.pop_back();
  return s;
}

}  // namespace

void BlockContext::fail(const Word* at, const std::string& message) const {
  SourceLocation where;
  where.file = file;
  where.line = line;
  where.column = at ? at->begin + 1 : 0;
  where.source_line = std::string(raw_line);
  throw InputError(where, message);
}

std::string gcode_name(int id) {
  if (id % 10 == 0) return fmt::format("G{}", id / 10);
  return fmt::format("G{}.{}", id / 10, id % 10);
}

namespace {

// The refusals of classify_block, out of line: the loop over the words stays
// small (it runs for every block) and the formatting is done only on error.
#define ABBE_COLD [[noreturn, gnu::cold, gnu::noinline]]

ABBE_COLD void fail_g_value(const BlockContext& where, const Word& w) {
  where.fail(&w, fmt::format("unknown G code G{}", format_number(w.value)));
}

ABBE_COLD void fail_g_code(const BlockContext& where, const Word& w, int id, const char* refusal) {
  if (refusal) where.fail(&w, fmt::format("{} ({}) is not supported", refusal, gcode_name(id)));
  where.fail(&w, fmt::format("unknown G code {}", gcode_name(id)));
}

ABBE_COLD void fail_g_twice(const BlockContext& where, const Word& w, GGroup group, int first,
                            int id) {
  if (group == GGroup::motion)
    where.fail(&w, fmt::format("two motion codes in one block ({} and {})", gcode_name(first),
                               gcode_name(id)));
  where.fail(&w, fmt::format("two G codes of the same modal group in one block ({} and {})",
                             gcode_name(first), gcode_name(id)));
}

ABBE_COLD void fail_m_value(const BlockContext& where, const Word& w) {
  where.fail(&w, fmt::format("unknown M code M{}", format_number(w.value)));
}

ABBE_COLD void fail_m_code(const BlockContext& where, const Word& w, int number) {
  where.fail(&w, fmt::format("M code M{} is not supported", number));
}

ABBE_COLD void fail_m_twice(const BlockContext& where, const Word& w, int first, int number) {
  where.fail(&w, fmt::format("two M codes of the same modal group in one block (M{} and M{})",
                             first, number));
}

ABBE_COLD void fail_letter(const BlockContext& where, const Word& w) {
  const char letter = w.letter;
  switch (letter) {
    case 'E':
      where.fail(&w, "E word is not supported");
    case 'N':
    case 'O':
      where.fail(&w, fmt::format("{} word in the middle of a block is not supported", letter));
    default:  // U V W
      where.fail(&w,
                 fmt::format("{} axis words are not supported (3-axis machines: X, Y, Z)", letter));
  }
}

ABBE_COLD void fail_repeated(const BlockContext& where, const Word& w) {
  where.fail(&w, fmt::format("repeated {} word in one block", w.letter));
}

ABBE_COLD void fail_unexpected(const BlockContext& where, const Word& w) {
  where.fail(&w, fmt::format("unexpected word '{}'", w.letter));
}

#undef ABBE_COLD

constexpr std::uint32_t letter_bit(char letter) { return 1U << BlockCodes::letter_index(letter); }

// Letters refused outright: U V W axes, E, and N or O after the start.
// (Rotary words A B C are checked by the interpreter: accepted while their
// axis does not move.)
constexpr std::uint32_t kRefusedLetters = letter_bit('U') | letter_bit('V') | letter_bit('W') |
                                          letter_bit('E') | letter_bit('N') | letter_bit('O');
// The letters a word may have besides G and M: A to Z, '^' and '@', less the refused ones.
constexpr std::uint32_t kAcceptedLetters =
    (((letter_bit('Z') << 1) - 1) | letter_bit('^') | letter_bit('@')) & ~kRefusedLetters;

}  // namespace

ABBE_HOT BlockCodes classify_block(const Block& block, const BlockContext& where) {
  BlockCodes codes;
  for (const Word& w : block.words) {
    const char letter = w.letter;
    if (letter == 'G') {
      // Rounded half up; values outside [0, 1000.1] are refused before
      // (they could only round outside [0, 10000]).
      const double tenfold = w.value * 10.0;
      const bool in_range = w.value >= 0.0 && w.value <= 1000.1;
      const double rounded = in_range ? round_half_up(tenfold) : 0.0;
      if (!in_range || std::abs(tenfold - rounded) > 1e-6 || rounded > 10000.0)
        fail_g_value(where, w);
      const int id = static_cast<int>(rounded);
      const GInfo info = g_info(id);
      if (!info.group) fail_g_code(where, w, id, info.refusal);
      const auto group = static_cast<std::size_t>(*info.group);
      CodeWord& slot = codes.g[group];
      const bool taken = (codes.g_mask >> group) & 1U;
      codes.g_mask |= 1U << group;
      if (taken) {
        // rs274ngc lets G80 share a block with another motion code, which wins.
        if (*info.group == GGroup::motion && (slot.code == gcode_id(80) || id == gcode_id(80))) {
          if (slot.code == gcode_id(80)) slot = CodeWord{id, &w};
          continue;
        }
        fail_g_twice(where, w, *info.group, slot.code, id);
      }
      slot = CodeWord{id, &w};
    } else if (letter == 'M') {
      const bool in_range = w.value >= 0.0 && w.value <= 1e6 + 1.0;
      const double rounded = in_range ? round_half_up(w.value) : 0.0;
      if (!in_range || std::abs(w.value - rounded) > 1e-9 || rounded > 1e6) fail_m_value(where, w);
      const int number = static_cast<int>(rounded);
      const auto group = m_group(number);
      if (!group) fail_m_code(where, w, number);
      const auto index = static_cast<std::size_t>(*group);
      if ((codes.m_mask >> index) & 1U) fail_m_twice(where, w, codes.m[index].code, number);
      codes.m_mask |= 1U << index;
      codes.m[index] = CodeWord{number, &w};
    } else {
      // One test for the common case: a letter of BlockCodes that is not refused.
      const unsigned index = BlockCodes::letter_index(letter);
      if (index > 30 || ((kAcceptedLetters >> index) & 1U) == 0) {
        if (index <= 30 && ((kRefusedLetters >> index) & 1U) != 0) fail_letter(where, w);
        fail_unexpected(where, w);
      }
      const std::uint32_t bit = 1U << index;
      if (codes.letter_mask & bit) fail_repeated(where, w);
      codes.letter_mask |= bit;
      codes.letters[index] = &w;
    }
  }
  return codes;
}

}  // namespace abbe::gcode
