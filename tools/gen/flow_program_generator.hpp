#pragma once
// Random but valid RS274/NGC programs with parameters, expressions and
// O-word control flow (LinuxCNC dialect), for the differential test against
// rs274 (tests/interop) and the fuzzer's seeds: numbered, named local and
// global parameters; expressions with every operator and function (never
// dividing by zero or leaving a function's domain); subroutines with
// arguments and return values, if/elseif/else, while with break/continue,
// do/while and repeat. Every coordinate stays within +-100 (mm) because
// each coordinate expression ends in MOD.
#include <random>
#include <string>
#include <vector>

namespace abbe::gen {

class FlowProgramGenerator {
 public:
  explicit FlowProgramGenerator(unsigned seed) : rng_(seed) {}

  std::string program();

 private:
  double uniform(double a, double b) { return std::uniform_real_distribution<double>(a, b)(rng_); }
  int pick(int n) { return std::uniform_int_distribution<int>(0, n - 1)(rng_); }
  bool chance(double p) { return uniform(0, 1) < p; }
  void line(const std::string& s);
  std::string number();
  std::string term(int depth);  // any finite value
  std::string coordinate();     // a value within +-40
  std::string condition();
  std::string new_label();
  void statement(int depth);
  void moves();

  std::mt19937 rng_;
  std::string text_;
  std::vector<std::string> params_;  // parameters that are defined
  std::vector<std::string> subs_;    // subroutine names
  int labels_ = 100;
  int indent_ = 0;
};

}  // namespace abbe::gen
