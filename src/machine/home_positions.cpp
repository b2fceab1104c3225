#include "abbe/machine/home_positions.hpp"

#include <fstream>
#include <sstream>

#include "home_positions_yaml.hpp"

namespace abbe::machine {

namespace detail {

HomePositions parse_home_positions(const io::YamlReader& r, const YAML::Node& root) {
  HomePositions home;
  if (const YAML::Node node = root["home_positions"]) {
    r.check_keys(node, "home_positions", {"G28", "G30"});
    if (node["G28"]) home.g28 = r.vec3(node["G28"], "home_positions.G28");
    if (node["G30"]) home.g30 = r.vec3(node["G30"], "home_positions.G30");
  }
  return home;
}

}  // namespace detail

HomePositions read_home_positions(const std::string& yaml_path) {
  std::ifstream in(yaml_path, std::ios::binary);
  if (!in) return {};
  std::ostringstream buffer;
  buffer << in.rdbuf();
  const std::string text = buffer.str();
  const io::YamlReader r(yaml_path, text);
  const YAML::Node root = r.load(text);
  if (!root.IsMap()) return {};
  return detail::parse_home_positions(r, root);
}

}  // namespace abbe::machine
