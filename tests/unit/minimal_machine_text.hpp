#pragma once
// The smallest complete machine file the machine-file tests edit: the
// sample's chain, travels and records, the table of tests/data/machines
// (parse it with kMachinesDir as the base folder), and the check that an
// edited file is refused with its line and field. Tests that count lines
// in their messages rely on it being 22 lines long.
#include <gtest/gtest.h>

#include <cstddef>
#include <string>

#include "abbe/io/input_error.hpp"
#include "abbe/machine/machine.hpp"

namespace abbe::testing {

inline const std::string kMachinesDir = std::string(ABBE_TEST_DATA_DIR) + "/machines";

inline const std::string kMinimalMachine = R"(name: t
chain: "w X' b Y Z t"
travel:
  x: [-990, 0]
  y: [-500, 0]
  z: [-460, 0]
tool_length: 130.0
table: sample-errors.csv
axes:
  X:
    measured_at: {x: -500.0, y: -256.0, z: -280.0, tool_length: 130.0}
    points:
      all: [-800.0, -256.0, -478.0]
  Y:
    measured_at: {x: -500.0, y: -250.0, z: -280.0, tool_length: 130.0}
    points:
      all: [-500.0, -250.0, -300.0]
  Z:
    measured_at: {x: -500.0, y: -250.0, z: -300.0, tool_length: 130.0}
    points:
      all: [-500.0, -250.0, -250.0]
)";

// `text` (read as "m.yaml" in kMachinesDir) must be refused naming the
// line, the field and a message that contains `says`.
inline void expect_machine_rejected(const std::string& text, std::size_t line,
                                    const std::string& field, const std::string& says) {
  try {
    machine::Machine::parse(text, "m.yaml", kMachinesDir);
    ADD_FAILURE() << "accepted:\n" << text;
  } catch (const InputError& e) {
    EXPECT_EQ(e.where().file, "m.yaml");
    EXPECT_EQ(e.where().line, line) << e.what();
    EXPECT_EQ(e.where().field, field) << e.what();
    EXPECT_NE(e.message().find(says), std::string::npos) << e.what();
  }
}

// A key appended to kMinimalMachine that must be refused (the machine
// file's optional sections). The parametrised test AppendedKeyRejects
// (machine_load_test.cpp) runs expect_machine_rejected on each; the sections'
// tests instantiate it with their cases.
struct AppendedKey {
  std::string key;  // appended to kMinimalMachine
  std::size_t line;
  std::string field;
  std::string says;
};

class AppendedKeyRejects : public ::testing::TestWithParam<AppendedKey> {};

}  // namespace abbe::testing
