#include "parameters.hpp"

#include <fstream>
#include <sstream>

#include "abbe/io/input_error.hpp"

namespace abbe::gcode::detail {

ParameterStore::ParameterStore() : numbered_(kCount, 0.0), locals_(1) {}

double ParameterStore::get(int n) const {
  if (live)
    if (const auto v = live(n)) return *v;
  return numbered_[static_cast<std::size_t>(n)];
}

std::optional<double> ParameterStore::find(const std::string& name) const {
  const bool global = !name.empty() && name[0] == '_';
  if (global && live_named)
    if (const auto v = live_named(name)) return v;
  const auto& scope = global ? globals_ : locals_.back();
  const auto it = scope.find(name);
  if (it == scope.end()) return std::nullopt;
  return it->second;
}

void ParameterStore::set(const std::string& name, double value) {
  auto& scope = (!name.empty() && name[0] == '_') ? globals_ : locals_.back();
  scope[name] = value;
}

void ParameterStore::enter_call(const std::vector<double>& arguments) {
  std::array<double, kCallArguments> saved{};
  for (std::size_t i = 0; i < saved.size(); ++i) {
    saved[i] = numbered_[i + 1];
    numbered_[i + 1] = i < arguments.size() ? arguments[i] : 0.0;
  }
  saved_.push_back(saved);
  locals_.emplace_back();
}

void ParameterStore::return_from_call() {
  if (saved_.empty()) return;
  for (std::size_t i = 0; i < saved_.back().size(); ++i) numbered_[i + 1] = saved_.back()[i];
  saved_.pop_back();
  locals_.pop_back();
}

void ParameterStore::read_var_file(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw InputError(SourceLocation{path, 0, 0, "", ""}, "cannot read the parameter file");
  std::string text;
  std::size_t line_number = 0;
  while (std::getline(in, text)) {
    ++line_number;
    std::istringstream fields(text);
    double number = 0.0;
    double value = 0.0;
    if (!(fields >> number)) continue;  // rs274 skips lines that do not start with a number
    if (!(fields >> value))
      throw InputError(SourceLocation{path, line_number, 0, "", text},
                       "parameter file: a number must be followed by its value");
    const int n = static_cast<int>(number);
    if (static_cast<double>(n) != number || !valid(n))
      throw InputError(SourceLocation{path, line_number, 0, "", text},
                       "parameter file: parameter number out of range (1 to 5601)");
    numbered_[static_cast<std::size_t>(n)] = value;
  }
}

}  // namespace abbe::gcode::detail
