#include "output_options.hpp"

namespace abbe::cli {

CLI::Option* add_output_option(CLI::App& sub, std::string& output, const std::string& what) {
  return sub.add_option("-o,--output", output, what + " (written atomically), - for stdout");
}

CLI::Option* add_format_option(CLI::App& sub, std::string& format,
                               const std::vector<std::string>& choices) {
  if (format.empty() && !choices.empty()) format = choices.front();
  std::string text;
  for (const auto& c : choices) text += (text.empty() ? "" : " or ") + c;
  return sub.add_option("--format", format, "Output format: " + text)
      ->check(CLI::IsMember(choices))
      ->capture_default_str();
}

CLI::Option* add_hidden_alias(CLI::App& sub, const std::string& name, std::string& target) {
  return sub.add_option(name, target, "")->group("");
}

std::FILE* summary_stream(const std::string& output) { return output == "-" ? stderr : stdout; }

}  // namespace abbe::cli
