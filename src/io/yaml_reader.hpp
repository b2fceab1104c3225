#pragma once
// YamlReader: the one way abbe reads its YAML files (machine files, truth
// files, overlays; private to the library — yaml-cpp stays out of the public
// headers). Every failure is an abbe::InputError naming the file, the line
// and column of the offending node (with its source line for the caret
// display) and the field path ("axes.X.points.all").
#include <yaml-cpp/yaml.h>

#include <Eigen/Core>
#include <set>
#include <string>
#include <vector>

namespace abbe::io {

class YamlReader {
 public:
  // `text` is the whole file: its lines are quoted in the messages.
  YamlReader(std::string file, const std::string& text);

  // The document; a syntax error is "YAML syntax error: …" at its place.
  YAML::Node load(const std::string& text) const;

  [[noreturn]] void fail(const YAML::Mark& mark, const std::string& field,
                         const std::string& message) const;
  // At the node (a missing node: the file only).
  [[noreturn]] void fail(const YAML::Node& node, const std::string& field,
                         const std::string& message) const;

  void expect_map(const YAML::Node& node, const std::string& field) const;
  // Every key of `node` is in `allowed` ("unknown key `k` (allowed: …)").
  void check_keys(const YAML::Node& node, const std::string& field,
                  const std::set<std::string>& allowed) const;
  std::string scalar_key(const YAML::Node& key, const std::string& field) const;
  // parent[key]; "missing key `key`" at the parent, field "field.key".
  YAML::Node required(const YAML::Node& parent, const std::string& key,
                      const std::string& field) const;

  double number(const YAML::Node& node, const std::string& field) const;  // finite
  std::string string(const YAML::Node& node, const std::string& field) const;
  long long integer(const YAML::Node& node, const std::string& field) const;
  std::vector<double> numbers(const YAML::Node& node, const std::string& field) const;
  std::vector<double> numbers(const YAML::Node& node, const std::string& field,
                              std::size_t n) const;  // exactly n
  Eigen::Vector3d vec3(const YAML::Node& node, const std::string& field) const;

  static std::string join(const std::string& a, const std::string& b);
  // A key repeated in a mapping: "duplicate key `k` (first on line n)" at the repeat.
  void refuse_duplicate_keys(const YAML::Node& node, const std::string& field) const;
  const std::string& file() const { return file_; }

 private:
  std::string file_;
  std::vector<std::string> lines_;
};

}  // namespace abbe::io
