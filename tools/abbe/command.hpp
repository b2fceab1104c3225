#pragma once
// Subcommand registry of the `abbe` CLI. Each tools/abbe/cmd_*.cpp registers
// one subcommand with a static CommandRegistrar, so adding a command touches
// no shared file.
#include <functional>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

namespace abbe::cli {

// Exit codes (documented in README and `abbe --help`).
// 4: a check the user asked for failed (verify --check, a tolerance check).
enum ExitCode : int { kOk = 0, kBadInput = 1, kUsage = 2, kInternal = 3, kCheckFailed = 4 };

struct GlobalOptions {
  int verbose = 0;  // -v count
  bool quiet = false;
};

// `setup` adds options to `sub` and returns the action run when the
// subcommand is selected; the action returns an exit code.
using CommandAction = std::function<int()>;
using CommandSetup = std::function<CommandAction(CLI::App& sub, const GlobalOptions& global)>;

struct CommandInfo {
  std::string name;
  std::string description;
  CommandSetup setup;
  int order;  // position in --help
};

std::vector<CommandInfo>& command_registry();

struct CommandRegistrar {
  CommandRegistrar(std::string name, std::string description, int order, CommandSetup setup) {
    command_registry().push_back({std::move(name), std::move(description), std::move(setup), order});
  }
};

}  // namespace abbe::cli
