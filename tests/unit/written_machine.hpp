#pragma once
// A virtual machine's campaign written as the files `abbe simulate` writes
// (errors.csv and machine.yaml in a temporary folder, `name` in its name) and
// read back with Machine::load: the machine the truth-comparison tests
// predict with.
#include <unistd.h>

#include <filesystem>
#include <string>

#include "abbe/machine/machine.hpp"
#include "abbe/sim/laser_campaign.hpp"
#include "abbe/sim/text_file.hpp"

namespace abbe::test {

inline machine::Machine written_machine(const sim::GeneratedMachine& g,
                                        const sim::CampaignResult& result,
                                        const std::string& name) {
  const auto dir =
      std::filesystem::temp_directory_path() / ("abbe_" + name + "_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  sim::write_text_file_atomically((dir / "errors.csv").string(), sim::table_to_csv(result));
  sim::write_text_file_atomically((dir / "machine.yaml").string(),
                                  sim::machine_to_yaml(g, result, "errors.csv"));
  machine::Machine m = machine::Machine::load((dir / "machine.yaml").string());
  std::filesystem::remove_all(dir);
  return m;
}

}  // namespace abbe::test
