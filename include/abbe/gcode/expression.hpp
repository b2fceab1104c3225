#pragma once
// Parameters and expressions of RS274/NGC (LinuxCNC dialect) as the X3
// grammar stores them in a Block: each expression is a short program in
// postfix order (operands before their operator), evaluated with a small
// stack by gcode::evaluate (src/gcode/expression.cpp) when the block runs.
// The grammar's rules give rs274ngc's precedence (** over * / MOD over + -
// over EQ NE GT GE LT LE over AND OR XOR, each level left-associative), so
// the order of the code is the order of evaluation.
#include <cstdint>
#include <string>
#include <vector>

namespace abbe::gcode {

enum class ExprOp : std::uint8_t {
  number,     // push value
  parameter,  // pop an index, push #index (numbered parameter)
  named,      // push #<names[arg]>
  exists,     // push 1 if #<names[arg]> is defined, else 0
  negate,     // unary minus
  // functions of one argument (angles in degrees, as rs274ngc)
  abs,
  acos,
  asin,
  cos,
  exp,
  fix,
  fup,
  ln,
  round,
  sin,
  sqrt,
  tan,
  atan,  // ATAN[a]/[b]: pops b, then a; pushes atan2(a, b) in degrees
  // binary operators: pop right, then left; push the result
  power,
  times,
  divide,
  modulo,
  plus,
  minus,
  eq,
  ne,
  gt,
  ge,
  lt,
  le,
  and_,
  or_,
  xor_,
};

struct ExprCode {
  ExprOp op = ExprOp::number;
  std::uint32_t column = 0;  // 0-based offset of the operator or operand in the line
  std::uint32_t arg = 0;     // name index (named, exists)
  double value = 0.0;        // number
};

// A piece of Block::code: [begin, end).
struct CodeRange {
  std::uint32_t begin = 0;
  std::uint32_t end = 0;
};

// A word whose value is an expression or a parameter (X#1, X[#1+2], X-#<a>):
// Block::words[word].value is only known once the code is evaluated.
struct WordExpression {
  std::uint32_t word = 0;
  CodeRange code;
};

// #n = value or #<name> = value. rs274ngc: every setting of a line takes
// effect after the whole line has been read (all reads see the old values).
struct ParameterSetting {
  std::int32_t name = -1;  // index into Block::names for #<name>, else -1
  CodeRange index;         // the code of n for #n
  CodeRange value;
  std::uint32_t column = 0;  // of the '#'
};

enum class OKeyword : std::uint8_t {
  none,
  sub,
  endsub,
  call,
  return_,
  do_,
  while_,
  endwhile,
  if_,
  elseif,
  else_,
  endif,
  break_,
  continue_,
  repeat,
  endrepeat,
};

// An O-word control-flow line: o100 if [...], o<name> call [1] [2], ...
struct OWord {
  OKeyword keyword = OKeyword::none;
  std::string label;  // "100" for o100 (leading zeros dropped), "name" for o<Name> (lower case)
  std::uint32_t column = 0;  // of the 'o'
  std::uint32_t keyword_column = 0;
  std::vector<CodeRange> args;  // the [...] after the keyword, in order
};

const char* o_keyword_name(OKeyword keyword);

}  // namespace abbe::gcode
