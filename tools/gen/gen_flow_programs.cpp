// gen_flow_programs COUNT DIR [FIRST_SEED]: writes COUNT random but valid
// programs with parameters, expressions and O-word control flow
// (flow_program_generator.hpp) as DIR/flow-NNNN.ngc, seeds FIRST_SEED.. (default 1).
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>

#include "tools/gen/flow_program_generator.hpp"

namespace abbe::gen {

void FlowProgramGenerator::line(const std::string& s) {
  text_ += std::string(static_cast<std::size_t>(2 * indent_), ' ') + s + "\n";
}

std::string FlowProgramGenerator::number() {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.3f", uniform(-9, 9));
  return buf;
}

std::string FlowProgramGenerator::term(int depth) {
  const int k = depth <= 0 ? pick(2) : pick(9);
  switch (k) {
    case 0:
      return number();
    case 1:
      return params_.empty()
                 ? number()
                 : params_[static_cast<std::size_t>(pick(static_cast<int>(params_.size())))];
    case 2: {
      static const char* kOps[] = {"+", "-", "*"};
      return "[" + term(depth - 1) + " " + kOps[pick(3)] + " " + term(depth - 1) + "]";
    }
    case 3: {
      static const char* kFunctions[] = {"SIN", "COS", "ABS", "FIX", "FUP", "ROUND"};
      return std::string(kFunctions[pick(6)]) + "[" + term(depth - 1) + "]";
    }
    case 4:
      return "SQRT[ABS[" + term(depth - 1) + "]]";
    case 5:
      return "ATAN[" + term(depth - 1) + "]/[" + number() + "]";
    case 6:
      return "[" + term(depth - 1) + " / [ABS[" + term(depth - 1) + "] + 1]]";
    case 7:
      return "[" + term(depth - 1) + " MOD " + std::to_string(1 + pick(9)) + "]";
    default:
      return "[[" + term(depth - 1) + " " + (chance(0.5) ? "GT" : "LE") + " " + term(depth - 1) +
             "] " + (chance(0.5) ? "AND" : "OR") + " [" + term(0) + " NE 0]]";
  }
}

std::string FlowProgramGenerator::coordinate() {
  // Always within [-40, 40): the MOD result is in [0, 80).
  return "[" + term(2) + " MOD 80 - 40]";
}

std::string FlowProgramGenerator::condition() {
  static const char* kRelations[] = {"EQ", "NE", "GT", "GE", "LT", "LE"};
  std::string c = "[" + term(1) + " " + kRelations[pick(6)] + " " + term(1) + "]";
  if (chance(0.3)) c = "[" + c + (chance(0.5) ? " AND " : " XOR ") + "[" + term(1) + " GT 0]]";
  return c;
}

std::string FlowProgramGenerator::new_label() { return "o" + std::to_string(labels_++); }

void FlowProgramGenerator::moves() {
  const int n = 1 + pick(3);
  for (int i = 0; i < n; ++i) {
    std::string block = chance(0.5) ? "G1" : "G0";
    block += " X" + coordinate();
    if (chance(0.8)) block += " Y" + coordinate();
    if (chance(0.4)) block += " Z" + coordinate();
    if (chance(0.3)) {  // a setting on a motion line takes effect after it
      const std::string p = "#" + std::to_string(31 + pick(5));
      block += " " + p + " = " + term(1);
      params_.push_back(p);
    }
    line(block);
  }
}

void FlowProgramGenerator::statement(int depth) {
  const int k = depth <= 0 ? pick(2) : pick(8);
  switch (k) {
    case 0: {
      std::string p;
      switch (pick(3)) {
        case 0:
          p = "#" + std::to_string(31 + pick(20));
          break;
        case 1:
          p = "#<v" + std::to_string(pick(5)) + ">";
          break;
        default:
          p = "#<_g" + std::to_string(pick(5)) + ">";
          break;
      }
      line(p + " = " + term(3));
      // A named parameter is read later only if it is surely defined: set
      // outside any if or loop (numbered parameters are always defined).
      if (p[1] != '<' || indent_ == 0) params_.push_back(p);
      break;
    }
    case 1:
      moves();
      break;
    case 2: {
      const std::string l = new_label();
      line(l + " if " + condition());
      ++indent_;
      statement(depth - 1);
      --indent_;
      if (chance(0.5)) {
        line(l + " elseif " + condition());
        ++indent_;
        statement(depth - 1);
        --indent_;
      }
      if (chance(0.5)) {
        line(l + " else");
        ++indent_;
        statement(depth - 1);
        --indent_;
      }
      line(l + " endif");
      break;
    }
    case 3: {  // while with a counter, maybe break / continue
      const std::string l = new_label();
      const std::string i = "#<_i" + std::to_string(labels_) + ">";
      line(i + " = 0");
      line(l + " while [" + i + " LT " + std::to_string(1 + pick(5)) + "]");
      ++indent_;
      line(i + " = [" + i + " + 1]");
      if (chance(0.4)) {
        const std::string m = new_label();
        line(m + " if [" + i + " EQ 2]");
        line("  " + l + (chance(0.5) ? " break" : " continue"));
        line(m + " endif");
      }
      statement(depth - 1);
      --indent_;
      line(l + " endwhile");
      if (indent_ == 0) params_.push_back(i);
      break;
    }
    case 4: {
      const std::string l = new_label();
      line(l + " repeat [" + std::to_string(pick(4)) + "]");
      ++indent_;
      statement(depth - 1);
      --indent_;
      line(l + " endrepeat");
      break;
    }
    case 5: {
      const std::string l = new_label();
      const std::string i = "#<_d" + std::to_string(labels_) + ">";
      line(i + " = 0");
      line(l + " do");
      ++indent_;
      line(i + " = [" + i + " + 1]");
      statement(depth - 1);
      --indent_;
      line(l + " while [" + i + " LT " + std::to_string(1 + pick(3)) + "]");
      if (indent_ == 0) params_.push_back(i);
      break;
    }
    default: {
      if (subs_.empty()) {
        moves();
        break;
      }
      std::string call =
          "o<" + subs_[static_cast<std::size_t>(pick(static_cast<int>(subs_.size())))] + "> call";
      const int args = pick(4);
      for (int a = 0; a < args; ++a) call += " [" + term(2) + "]";
      line(call);
      if (chance(0.5)) {
        line("G1 X[#<_value> MOD 80 - 40]");
      }
      break;
    }
  }
}

std::string FlowProgramGenerator::program() {
  text_.clear();
  line("G21 G90 G17 G94 F300");
  line("G0 X0 Y0 Z0");
  // Subroutines first: their bodies use only the arguments #1..#3 and locals.
  const int subs = 1 + pick(2);
  for (int s = 0; s < subs; ++s) {
    const std::string name = "s" + std::to_string(s);
    line("o<" + name + "> sub");
    ++indent_;
    const std::vector<std::string> outer = params_;
    params_ = {"#1", "#2", "#3"};
    line("#<t> = " + term(2));
    params_.push_back("#<t>");
    moves();
    if (chance(0.5)) {
      const std::string l = new_label();
      line(l + " if [#1 GT 0]");
      line("  o<" + name + "> return [#1 + #<t>]");
      line(l + " endif");
    }
    moves();
    params_ = outer;
    --indent_;
    line("o<" + name + "> endsub [#2]");
    subs_.push_back(name);
  }
  const int statements = 8 + pick(10);
  for (int i = 0; i < statements; ++i) statement(3);
  line("M2");
  return text_;
}

}  // namespace abbe::gen

int main(int argc, char** argv) {
  if (argc != 3 && argc != 4) {
    std::fprintf(stderr, "usage: gen_flow_programs COUNT DIR [FIRST_SEED]\n");
    return 2;
  }
  const int count = std::atoi(argv[1]);
  const unsigned first = argc == 4 ? static_cast<unsigned>(std::atoi(argv[3])) : 1u;
  for (int i = 0; i < count; ++i) {
    char name[64];
    std::snprintf(name, sizeof name, "/flow-%04d.ngc", i);
    std::ofstream out(std::string(argv[2]) + name);
    out << abbe::gen::FlowProgramGenerator(first + static_cast<unsigned>(i)).program();
    if (!out) {
      std::fprintf(stderr, "gen_flow_programs: cannot write %s%s\n", argv[2], name);
      return 1;
    }
  }
  return 0;
}
