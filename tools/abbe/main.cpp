// abbe — toolpath error predictor and NC-code post-processor.
#include <spdlog/sinks/stdout_color_sinks.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <iostream>
#include <map>

#include "abbe/io/input_error.hpp"
#include "command.hpp"
#include "heap.hpp"

namespace abbe::cli {
std::vector<CommandInfo>& command_registry() {
  static std::vector<CommandInfo> registry;
  return registry;
}
}  // namespace abbe::cli

int main(int argc, char** argv) {
  using namespace abbe::cli;
  keep_large_buffers_in_heap();
  CLI::App app{
      "abbe: predict how far a 3-axis machine tool deviates along an NC program, "
      "and why.\n"
      "Exit codes: 0 ok, 1 bad input, 2 usage, 3 internal error, 4 a check failed."};
  app.set_version_flag("--version", std::string("abbe ") + ABBE_VERSION);
  app.require_subcommand(1);
  GlobalOptions global;
  app.add_flag("-v,--verbose", global.verbose, "More log output (repeat for debug)");
  app.add_flag("-q,--quiet", global.quiet, "Only errors on stderr");
  // Global options anywhere on the line: an option a subcommand does not know
  // falls through to its parent (subcommands inherit this setting).
  app.fallthrough();

  auto logger = spdlog::stderr_color_mt("abbe");
  spdlog::set_default_logger(logger);
  spdlog::set_pattern("abbe: %^%l%$: %v");

  auto& registry = command_registry();
  std::sort(registry.begin(), registry.end(),
            [](const CommandInfo& a, const CommandInfo& b) { return a.order < b.order; });
  std::map<CLI::App*, CommandAction> actions;
  for (auto& info : registry) {
    CLI::App* sub = app.add_subcommand(info.name, info.description);
    actions[sub] = info.setup(*sub, global);
  }
  // Set after the subcommands: CLI11 copies the footer into subcommands added later.
  app.footer(
      "Examples:\n"
      "  abbe predict nc-samples/thesis-toolpath-1.ngc --machine machines/sample/machine.yaml "
      "--model all\n"
      "  abbe report predict nc-samples/thesis-toolpath-1.ngc --machine "
      "machines/sample/machine.yaml -o report.html\n"
      "  abbe COMMAND --help shows the options and an example of each command.\n"
      "A progress bar appears on stderr for long jobs when it is a terminal (not with -q).\n"
      "Global options (-v, -q) go anywhere on the line. Every command that writes data takes\n"
      "-o FILE (- for stdout; the summary then goes to stderr); inputs may be - (stdin).\n"
      "Exit codes: 0 ok, 1 bad input (file, line and column named), 2 usage, 3 internal error,\n"
      "4 a check failed (verify --check).\n"
      "Walk-through: docs/getting-started.md");

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    int rc = app.exit(e);
    return rc == 0 ? kOk : kUsage;
  }
  if (global.quiet)
    spdlog::set_level(spdlog::level::err);
  else if (global.verbose >= 2)
    spdlog::set_level(spdlog::level::trace);
  else if (global.verbose == 1)
    spdlog::set_level(spdlog::level::debug);
  else
    spdlog::set_level(spdlog::level::info);

  try {
    for (auto& [sub, action] : actions)
      if (sub->parsed()) return action();
  } catch (const abbe::InputError& e) {
    std::cerr << e.what() << "\n";
    return kBadInput;
  } catch (const std::exception& e) {
    std::cerr << "abbe: internal error: " << e.what() << "\n";
    return kInternal;
  }
  return kUsage;
}
