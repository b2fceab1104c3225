#include "fanuc_dialect.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>

#include "abbe/io/units.hpp"

namespace abbe::gcode {

std::optional<Dialect> dialect_from_name(std::string_view name) {
  if (name == "linuxcnc") return Dialect::linuxcnc;
  if (name == "fanuc") return Dialect::fanuc;
  return std::nullopt;
}

const char* dialect_name(Dialect dialect) {
  return dialect == Dialect::fanuc ? "fanuc" : "linuxcnc";
}

std::optional<IntegerNumbers> integer_numbers_from_name(std::string_view name) {
  if (name == "increment") return IntegerNumbers::least_increment;
  if (name == "units") return IntegerNumbers::whole_units;
  return std::nullopt;
}

const Word* subprogram_flow_word(const Block& block) {
  for (const Word& w : block.words)
    if (w.letter == 'M' && (w.value == 98.0 || w.value == 99.0)) return &w;
  return nullptr;
}

namespace detail {

namespace {

// Least input increment of increment system IS-B (Fanuc's default).
constexpr double kIncrementMm = 1e-3;
constexpr double kIncrementInch = 1e-4;
// A dwell written without a decimal point is in milliseconds (Fanuc G04 P,
// G82/G89 P; Haas reads P with a point as seconds).
constexpr double kSecondsPerMillisecond = 1e-3;
constexpr long kMaxRepeats = 9999;  // L of M98 (four digits)

int code_of(const Word& w) { return static_cast<int>(std::lround(w.value * 10.0)); }

bool written_with_point(const Word& w, std::string_view raw_line) {
  if (w.end > raw_line.size() || w.number_begin > w.end) return true;  // not from this text
  return raw_line.substr(w.number_begin, w.end - w.number_begin).find('.') !=
         std::string_view::npos;
}

const Word* find_code(const Block& block, char letter, int id) {
  for (const Word& w : block.words)
    if (w.letter == letter && code_of(w) == id) return &w;
  return nullptr;
}

const Word* find_letter(const Block& block, char letter) {
  for (const Word& w : block.words)
    if (w.letter == letter) return &w;
  return nullptr;
}

long whole_number(const Word& w, const BlockContext& ctx, const char* what) {
  if (!(w.value >= 0.0) || std::abs(w.value - std::round(w.value)) > 1e-9 || w.value > 1e8)
    ctx.fail(&w, fmt::format("{} must be a non-negative integer", what));
  return std::lround(w.value);
}

// Fanuc/Haas codes that change how the control moves, not where: look-ahead
// (G05.1 Q1 AI contour control, G08 P1 look-ahead, Haas G05 P high-speed
// machining, G103 P block look-ahead, G187 P smoothing) and the cancel codes
// of functions abbe never turns on. Carried: removed with their words.
struct CarriedCode {
  int id;
  const char* letters;  // the words that belong to it
};
constexpr std::array<CarriedCode, 10> kCarried{{
    {gcode_id(5), "P"},
    {gcode_id(5, 1), "QR"},
    {gcode_id(8), "P"},
    {gcode_id(103), "P"},
    {gcode_id(187), "PE"},  // Haas: P smoothing level, E corner tolerance
    {gcode_id(13, 1), ""},  // polar coordinate interpolation cancel
    {gcode_id(15), ""},     // polar coordinate command cancel
    {gcode_id(50), ""},     // scaling cancel
    {gcode_id(50, 1), ""},  // programmable mirror image cancel
    {gcode_id(69), ""},     // coordinate rotation cancel
}};

struct RefusedCode {
  int id;
  const char* name;
};
constexpr std::array<RefusedCode, 12> kRefused{{
    {gcode_id(12, 1), "polar coordinate interpolation"},
    {gcode_id(87), "back boring (Fanuc's shift Q)"},
    {gcode_id(16), "polar coordinate command"},
    {gcode_id(51), "scaling"},
    {gcode_id(51, 1), "programmable mirror image"},
    {gcode_id(54, 1), "additional work offsets"},
    {gcode_id(154), "additional work offsets"},
    {gcode_id(65), "custom macro call"},
    {gcode_id(66), "modal custom macro call"},
    {gcode_id(66, 1), "modal custom macro call"},
    {gcode_id(68), "coordinate rotation"},
    {gcode_id(68, 2), "tilted working plane"},
}};

bool is_fanuc_cycle(int id) {
  return id == gcode_id(73) || id == gcode_id(74) || id == gcode_id(76) ||
         (id >= gcode_id(81) && id <= gcode_id(89) && id % 10 == 0);
}

bool is_length_letter(char letter) {
  switch (letter) {
    case 'X':
    case 'Y':
    case 'Z':
    case 'I':
    case 'J':
    case 'K':
    case 'R':
    case 'Q':
      return true;
    default:
      return false;
  }
}

}  // namespace

FanucFlow fanuc_flow(const Block& block, const BlockContext& ctx) {
  FanucFlow flow;
  const Word* m98 = find_code(block, 'M', gcode_id(98));
  const Word* m99 = find_code(block, 'M', gcode_id(99));
  if (const Word* m97 = find_code(block, 'M', gcode_id(97)))
    ctx.fail(m97,
             "local subprogram call (M97) is not supported; use M98 with an O-numbered program");
  if (const Word* m198 = find_code(block, 'M', gcode_id(198)))
    ctx.fail(m198, "subprogram call from external memory (M198) is not supported");
  if (m98 && m99) ctx.fail(m99, "M98 and M99 in one block");
  if (m98) {
    flow.at = m98;
    const Word* p = find_letter(block, 'P');
    if (!p) ctx.fail(m98, "M98 without P (the program number to call)");
    const long number = whole_number(*p, ctx, "P of M98 (program number)");
    if (const Word* l = find_letter(block, 'L')) {
      flow.call = number;
      flow.repeats = whole_number(*l, ctx, "L of M98 (repeat count)");
      if (flow.repeats > kMaxRepeats)
        ctx.fail(l, fmt::format("L of M98 (repeat count) is above {}", kMaxRepeats));
    } else if (number > 9999) {
      // Fanuc's 8-digit form: P<repeats, 4 digits><program, 4 digits>.
      flow.repeats = number / 10000;
      flow.call = number % 10000;
    } else {
      flow.call = number;
    }
  }
  if (m99) {
    flow.at = m99;
    flow.ret = true;
    if (const Word* p = find_letter(block, 'P'))
      ctx.fail(p, "M99 P (return to a sequence number) is not supported");
  }
  return flow;
}

void adapt_fanuc_block(Block& block, std::string_view raw_line, bool inch, IntegerNumbers integers,
                       const BlockContext& ctx) {
  if (block.words.empty()) return;
  for (const Word& w : block.words) {
    if (w.letter == '@' || w.letter == '^')
      ctx.fail(&w, fmt::format("polar coordinates ('{}') are not supported in the Fanuc dialect",
                               w.letter));
    // LinuxCNC's M codes without a Fanuc meaning (overrides, M61, M70-M73).
    if (w.letter == 'M' &&
        ((w.value >= 50 && w.value <= 53) || w.value == 61 || (w.value >= 70 && w.value <= 73)))
      ctx.fail(&w, fmt::format("M code M{} is not supported", w.value));
  }
  for (const RefusedCode& r : kRefused)
    if (const Word* w = find_code(block, 'G', r.id))
      ctx.fail(w, fmt::format("{} ({}) is not supported", r.name, gcode_name(r.id)));

  // Which words go: carried codes with their letters, M98/M99 with P and L.
  std::uint32_t drop_letters = 0;  // bit i: letter 'A' + i
  auto letter_bit = [](char c) { return 1U << static_cast<unsigned>(c - 'A'); };
  bool drops_code = false;
  bool other_codes = false;  // G codes that might use the dropped letters
  bool cycle = false;
  bool dwell = false;
  bool cycle_dwell = false;
  std::optional<bool> block_inch;
  for (const Word& w : block.words) {
    if (w.letter == 'M' && (code_of(w) == gcode_id(98) || code_of(w) == gcode_id(99))) {
      drop_letters |= letter_bit('P') | letter_bit('L');
      drops_code = true;
      continue;
    }
    if (w.letter != 'G') continue;
    const int id = code_of(w);
    const auto carried = std::find_if(kCarried.begin(), kCarried.end(),
                                      [id](const CarriedCode& c) { return c.id == id; });
    if (carried != kCarried.end()) {
      for (const char* l = carried->letters; *l; ++l) drop_letters |= letter_bit(*l);
      drops_code = true;
      continue;
    }
    if (id == gcode_id(20)) block_inch = true;
    if (id == gcode_id(21)) block_inch = false;
    if (id == gcode_id(4)) dwell = true;
    if (is_fanuc_cycle(id)) cycle = true;
    if (id == gcode_id(74) || id == gcode_id(82) || id == gcode_id(84) || id == gcode_id(86) ||
        id == gcode_id(89))
      cycle_dwell = true;
    if (id == gcode_id(4) || id == gcode_id(10) || is_fanuc_cycle(id) || id == gcode_id(2) ||
        id == gcode_id(3) || id == gcode_id(64))
      other_codes = true;
  }
  if (drops_code && drop_letters != 0 && other_codes) {
    for (const Word& w : block.words)
      if (w.letter != 'G' && w.letter != 'M' && (drop_letters & letter_bit(w.letter)))
        ctx.fail(&w, fmt::format("word {} is ambiguous: a look-ahead, smoothing or subprogram "
                                 "code and a code that reads {} share this block",
                                 w.letter, w.letter));
  }

  const double increment = block_inch.value_or(inch) ? kIncrementInch : kIncrementMm;
  const bool scale_integers = integers == IntegerNumbers::least_increment;
  std::size_t kept = 0;
  for (std::size_t i = 0; i < block.words.size(); ++i) {
    Word w = block.words[i];
    bool drop = false;
    if (w.letter == 'G') {
      const int id = code_of(w);
      drop = std::any_of(kCarried.begin(), kCarried.end(),
                         [id](const CarriedCode& c) { return c.id == id; });
    } else if (w.letter == 'M') {
      // M98/M99 (the runner follows them) and M29 (rigid tapping mode: the
      // S word stays the spindle speed, the tapping cycle is G84/G74).
      drop = code_of(w) == gcode_id(98) || code_of(w) == gcode_id(99) || code_of(w) == gcode_id(29);
    } else if (w.letter != 'N' && (drop_letters & letter_bit(w.letter))) {
      drop = true;
    } else {
      const bool point = written_with_point(w, raw_line);
      if (dwell && (w.letter == 'P' || w.letter == 'X')) {
        // G04 P<ms> / G04 X<s>: RS274/NGC's G4 P takes seconds.
        if (!point) w.value *= kSecondsPerMillisecond;
        w.letter = 'P';
      } else if (cycle_dwell && w.letter == 'P') {
        if (!point) w.value *= kSecondsPerMillisecond;
      } else if (cycle && w.letter == 'K') {
        w.letter = 'L';  // Fanuc's repeat count of a canned cycle
      } else if (scale_integers && !point && is_length_letter(w.letter)) {
        w.value *= increment;
      }
    }
    if (!drop) block.words[kept++] = w;
  }
  block.words.resize(kept);
}

}  // namespace detail

}  // namespace abbe::gcode
