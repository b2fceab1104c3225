#pragma once
// The parameters of an RS274/NGC program as LinuxCNC's rs274ngc keeps them:
// numbered #1..#5601 (0 until set), named globals #<_name> and named locals
// #<name> (one scope per subroutine call level), and the subroutine
// arguments #1..#30 saved and restored around a call. Predefined parameters
// that mirror the interpreter's state (#5220 coordinate system, #5221.. work
// offsets, #5400 tool, #5420.. position) are read from it through `live`.
#include <array>
#include <functional>
#include <optional>
#include <string>
#include <unordered_map>
#include <vector>

namespace abbe::gcode::detail {

class ParameterStore {
 public:
  // #1 .. #5601, as LinuxCNC 2.9 (RS274NGC_MAX_PARAMETERS 5602).
  static constexpr int kCount = 5602;
  static constexpr int kCallArguments = 30;  // #1 .. #30 are a subroutine's arguments

  ParameterStore();

  static bool valid(int n) { return n >= 1 && n < kCount; }
  double get(int n) const;  // n valid
  void set(int n, double value) { numbered_[static_cast<std::size_t>(n)] = value; }

  // nullopt if not defined (locals of the current call level, or globals
  // for "_..."; a predefined global comes from `live_named`).
  std::optional<double> find(const std::string& name) const;
  void set(const std::string& name, double value);
  // A predefined named parameter (#<_x>, …): read-only, rs274ngc refuses to
  // assign it.
  bool read_only(const std::string& name) const {
    return !name.empty() && name[0] == '_' && live_named && live_named(name).has_value();
  }

  // A subroutine call: saves #1..#30, sets them to `arguments` (the rest to 0)
  // and opens a new scope of local names; return_from_call undoes both.
  void enter_call(const std::vector<double>& arguments);
  void return_from_call();

  // rs274's parameter file: "number value" per line (other lines ignored, as rs274 does).
  void read_var_file(const std::string& path);

  // Predefined parameters computed from the interpreter (nullopt: stored value).
  std::function<std::optional<double>(int)> live;
  std::function<std::optional<double>(const std::string&)> live_named;

 private:
  std::vector<double> numbered_;
  std::unordered_map<std::string, double> globals_;
  std::vector<std::unordered_map<std::string, double>> locals_;
  std::vector<std::array<double, kCallArguments>> saved_;
};

}  // namespace abbe::gcode::detail
