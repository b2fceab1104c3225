// SHA-256 (FIPS 180-4 test vectors), the provenance block of compensated
// programs (written, read back, refused twice) and the travel check.
#include "abbe/compensate/provenance.hpp"

#include <gtest/gtest.h>

#include <sstream>
#include <string>

#include "abbe/compensate/program_compensator.hpp"
#include "abbe/io/input_error.hpp"
#include "abbe/io/sha256.hpp"
#include "abbe/machine/travel_check.hpp"

namespace abbe {
namespace {

TEST(Sha256, StandardVectors) {
  // FIPS 180-4 / NIST CSRC example values: "", "abc", the two-block message
  // (the same digests as coreutils sha256sum).
  EXPECT_EQ(io::sha256_hex(""), "e3b0c44298fc1c149afbf4c8996fb92427ae41e4649b934ca495991b7852b855");
  EXPECT_EQ(io::sha256_hex("abc"),
            "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad");
  EXPECT_EQ(io::sha256_hex("abcdbcdecdefdefgefghfghighijhijkijkljklmklmnlmnomnopnopq"),
            "248d6a61d20638b8e5c026930c3e6039a33ce45964ff2167f6ecedd419db06c1");
  // One million 'a' fed in uneven pieces: the block boundaries do not matter.
  io::Sha256 h;
  const std::string chunk(997, 'a');
  std::size_t left = 1000000;
  while (left > 0) {
    const std::size_t n = std::min(left, chunk.size());
    h.update(chunk.data(), n);
    left -= n;
  }
  EXPECT_EQ(h.hex(), "cdc76e5c9914fb9281a1c7e284d73e67f1809a48a497200e046d39ccc7112cd0");
}

compensate::Provenance sample() {
  compensate::Provenance p;
  p.version = "1.2.3";
  p.files = {{"machine-file", std::string(64, 'a'), "m/machine.yaml"},
             {"table-file", std::string(64, 'b'), "m/table.csv"}};
  p.model = "ae-arm";
  p.tol_um = 1.0;
  p.step_mm = 5.0;
  gcode::InterpreterConfig config;
  config.default_tool_length = 130.0;
  config.tool_lengths[1] = 200.0;
  config.initial_position = Eigen::Vector3d(0.0, 0.0, -130.0);
  p.setup = compensate::setup_lines(config);
  p.date = "2026-01-02T03:04:05Z";
  return p;
}

TEST(Provenance, WrittenAndReadBack) {
  const compensate::Provenance p = sample();
  const std::string text = "%\r\n" + compensate::format_provenance(p, "\r\n") + "G0 X1\r\nM2\r\n";
  EXPECT_EQ(text.find("(abbe-compensated by abbe 1.2.3:"), 3u);
  std::istringstream in(text);
  const auto r = compensate::read_provenance(in);
  ASSERT_TRUE(r);
  EXPECT_EQ(r->line, 2u);
  EXPECT_EQ(r->version, "1.2.3");
  ASSERT_EQ(r->files.size(), 2u);
  EXPECT_EQ(r->files[1].role, "table-file");
  EXPECT_EQ(r->files[1].sha256, std::string(64, 'b'));
  EXPECT_EQ(r->files[1].path, "m/table.csv");
  EXPECT_EQ(r->model, "ae-arm");
  EXPECT_EQ(r->date, "2026-01-02T03:04:05Z");
  EXPECT_DOUBLE_EQ(r->tol_um, 1.0);
  EXPECT_DOUBLE_EQ(r->step_mm, 5.0);
  EXPECT_NO_THROW(compensate::check_machine_files(*r, "c.ngc", p.files));
  EXPECT_NO_THROW(compensate::check_setup(*r, "c.ngc", p.setup));
  auto other = p.files;
  other[0].sha256 = std::string(64, 'c');
  EXPECT_THROW(compensate::check_machine_files(*r, "c.ngc", other), InputError);
  gcode::InterpreterConfig config;
  config.default_tool_length = 100.0;
  EXPECT_THROW(compensate::check_setup(*r, "c.ngc", compensate::setup_lines(config)), InputError);
}

TEST(Provenance, AProgramWithoutTheBlock) {
  std::istringstream in("G21\n(abbe-compensated by abbe 1: late)\nM2\n");
  EXPECT_FALSE(compensate::read_provenance(in));
  EXPECT_TRUE(compensate::carries_provenance("G0 X1 (abbe-compensated by abbe 1: x)"));
  EXPECT_FALSE(compensate::carries_provenance("G0 X1 (abbe)"));
}

TEST(Provenance, PathsCannotEndTheComment) {
  compensate::Provenance p = sample();
  p.files[0].path = "a(b)c.yaml";
  p.model = "ae-arm (x)";
  const std::string text = compensate::format_provenance(p, "\n");
  std::istringstream in(text);
  std::string line;
  while (std::getline(in, line)) {
    EXPECT_EQ(line.find('('), 0u) << line;
    EXPECT_EQ(line.find(')'), line.size() - 1) << line;
  }
  EXPECT_EQ(compensate::file_fingerprint("x", "/dev/null").sha256, io::sha256_hex(""));
}

TEST(TravelCheck, CountsPointsPerAxisWithTheToolLength) {
  machine::TravelCheck t(
      {machine::Travel{-990, 0}, machine::Travel{-500, 0}, machine::Travel{-460, 0}});
  // Tip at Z −130 with L = 130: spindle at 0, inside.
  EXPECT_TRUE(t.add(Eigen::Vector3d(-10, -10, -130), 130.0, 1));
  EXPECT_FALSE(t.add(Eigen::Vector3d(-2000, -10, -130), 130.0, 2));
  EXPECT_FALSE(t.add(Eigen::Vector3d(-2000, 10, -100), 130.0, 2));  // X, Y and Z (s_z = 30)
  EXPECT_FALSE(t.add(Eigen::Vector3d(-10, -10, -600), 130.0, 7));   // Z: s_z = −470
  EXPECT_EQ(t.points(), 4u);
  EXPECT_EQ(t.outside(), 3u);
  EXPECT_EQ(t.outside_per_axis()[0], 2u);
  EXPECT_EQ(t.outside_per_axis()[1], 1u);
  EXPECT_EQ(t.outside_per_axis()[2], 2u);
  EXPECT_EQ(t.first_lines(), (std::vector<std::size_t>{2, 7}));
  EXPECT_EQ(
      t.text(),
      "3 of 4 points outside the travel (points per axis: X 2, Y 1, Z 2), first on lines 2, 7");
  EXPECT_EQ(t.describe(Eigen::Vector3d(-10, -10, -130), 130.0), "");
}

}  // namespace
}  // namespace abbe
