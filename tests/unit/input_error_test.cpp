#include "abbe/io/input_error.hpp"

#include <gtest/gtest.h>

TEST(InputError, NamesFileLineColumnAndShowsCaret) {
  abbe::SourceLocation where{"prog.nc", 12, 5, "", "G1 XQ10"};
  abbe::InputError e(where, "bad number");
  std::string msg = e.what();
  EXPECT_NE(msg.find("prog.nc:12:5: error: bad number"), std::string::npos) << msg;
  EXPECT_NE(msg.find("G1 XQ10\n      ^"), std::string::npos) << msg;
}

TEST(InputError, NamesField) {
  abbe::InputError e({"m.yaml", 3, 0, "travel.x", ""}, "must be positive");
  EXPECT_EQ(std::string(e.what()), "m.yaml:3 [travel.x]: error: must be positive");
}
