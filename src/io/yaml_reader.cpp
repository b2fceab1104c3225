#include "yaml_reader.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <cmath>
#include <map>
#include <sstream>

#include "abbe/io/input_error.hpp"

namespace abbe::io {

YamlReader::YamlReader(std::string file, const std::string& text) : file_(std::move(file)) {
  std::istringstream in(text);
  std::string l;
  while (std::getline(in, l)) {
    if (!l.empty() && l.back() == '\r') l.pop_back();
    lines_.push_back(l);
  }
}

YAML::Node YamlReader::load(const std::string& text) const {
  YAML::Node root;
  try {
    root = YAML::Load(text);
  } catch (const YAML::ParserException& e) {
    fail(e.mark, "", fmt::format("YAML syntax error: {}", e.msg));
  }
  refuse_duplicate_keys(root, "");
  return root;
}

// yaml-cpp keeps both entries of a repeated key; a lookup finds the first,
// an iteration the last: either way one value is silently lost.
void YamlReader::refuse_duplicate_keys(const YAML::Node& node, const std::string& field) const {
  if (node.IsSequence()) {
    std::size_t i = 0;
    for (const auto& item : node) refuse_duplicate_keys(item, fmt::format("{}[{}]", field, i++));
    return;
  }
  if (!node.IsMap()) return;
  std::map<std::string, YAML::Mark> seen;
  for (const auto& kv : node) {
    if (kv.first.IsScalar()) {
      const std::string key = kv.first.Scalar();
      const auto [it, fresh] = seen.emplace(key, kv.first.Mark());
      if (!fresh)
        fail(kv.first, join(field, key),
             fmt::format("duplicate key `{}` (first on line {})", key, it->second.line + 1));
      refuse_duplicate_keys(kv.second, join(field, key));
    } else {
      refuse_duplicate_keys(kv.second, field);
    }
  }
}

void YamlReader::fail(const YAML::Mark& mark, const std::string& field,
                      const std::string& message) const {
  SourceLocation where{file_, 0, 0, field, ""};
  if (mark.line >= 0) {
    where.line = static_cast<std::size_t>(mark.line) + 1;
    where.column = static_cast<std::size_t>(mark.column) + 1;
    if (static_cast<std::size_t>(mark.line) < lines_.size())
      where.source_line = lines_[static_cast<std::size_t>(mark.line)];
  }
  throw InputError(where, message);
}

void YamlReader::fail(const YAML::Node& node, const std::string& field,
                      const std::string& message) const {
  fail(node.IsDefined() ? node.Mark() : YAML::Mark::null_mark(), field, message);
}

void YamlReader::expect_map(const YAML::Node& node, const std::string& field) const {
  if (!node.IsMap()) fail(node, field, fmt::format("`{}` must be a mapping", field));
}

void YamlReader::check_keys(const YAML::Node& node, const std::string& field,
                            const std::set<std::string>& allowed) const {
  expect_map(node, field);
  for (const auto& kv : node) {
    const std::string key = scalar_key(kv.first, field);
    if (!allowed.count(key))
      fail(kv.first, join(field, key),
           fmt::format("unknown key `{}` (allowed: {})", key, fmt::join(allowed, ", ")));
  }
}

std::string YamlReader::scalar_key(const YAML::Node& key, const std::string& field) const {
  if (!key.IsScalar()) fail(key, field, "keys must be plain scalars");
  return key.Scalar();
}

YAML::Node YamlReader::required(const YAML::Node& parent, const std::string& key,
                                const std::string& field) const {
  expect_map(parent, field);
  const YAML::Node n = parent[key];
  if (!n) fail(parent, join(field, key), fmt::format("missing key `{}`", key));
  return n;
}

double YamlReader::number(const YAML::Node& node, const std::string& field) const {
  if (!node.IsScalar()) fail(node, field, "expected a number");
  double v = 0.0;
  try {
    v = node.as<double>();
  } catch (const YAML::Exception&) {
    fail(node, field, fmt::format("\"{}\" is not a number", node.Scalar()));
  }
  if (!std::isfinite(v)) fail(node, field, "the value must be finite (no NaN or inf)");
  return v;
}

std::string YamlReader::string(const YAML::Node& node, const std::string& field) const {
  if (!node.IsScalar()) fail(node, field, "expected a string");
  return node.Scalar();
}

long long YamlReader::integer(const YAML::Node& node, const std::string& field) const {
  if (!node.IsScalar()) fail(node, field, "expected an integer");
  try {
    return node.as<long long>();
  } catch (const YAML::Exception&) {
    fail(node, field, fmt::format("\"{}\" is not an integer", node.Scalar()));
  }
}

std::vector<double> YamlReader::numbers(const YAML::Node& node, const std::string& field) const {
  if (!node.IsSequence()) fail(node, field, "expected a list of numbers");
  std::vector<double> out;
  for (std::size_t i = 0; i < node.size(); ++i)
    out.push_back(number(node[i], fmt::format("{}[{}]", field, i)));
  return out;
}

std::vector<double> YamlReader::numbers(const YAML::Node& node, const std::string& field,
                                        std::size_t n) const {
  if (!node.IsSequence() || node.size() != n)
    fail(node, field, fmt::format("expected a list of {} numbers", n));
  return numbers(node, field);
}

Eigen::Vector3d YamlReader::vec3(const YAML::Node& node, const std::string& field) const {
  const auto v = numbers(node, field, 3);
  return {v[0], v[1], v[2]};
}

std::string YamlReader::join(const std::string& a, const std::string& b) {
  return a.empty() ? b : a + "." + b;
}

}  // namespace abbe::io
