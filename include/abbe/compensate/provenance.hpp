#pragma once
// The provenance block of a compensated program: comment lines at its top
// saying which abbe, machine files (with the SHA-256 of their content),
// model, overlay, tolerance, step and setup (work offsets, tool lengths,
// start point) the correction was computed for, and when. `compensate`
// writes it and refuses a program that carries it (compensating twice
// doubles the correction); `verify` reads it and refuses machine files
// whose content differs (docs/compensation.md, "Running it on a machine").
#include <cstddef>
#include <istream>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "abbe/gcode/interpreter.hpp"
#include "abbe/machine/machine.hpp"

namespace abbe::compensate {

// The first line of the block starts with this; no other program does.
inline constexpr std::string_view kProvenanceMarker = "(abbe-compensated";

struct FileFingerprint {
  std::string role;    // "machine-file", "table-file", "overlay-file"
  std::string sha256;  // 64 hex digits
  std::string path;    // as given (parentheses replaced: it sits in a comment)
};

struct Provenance {
  std::string version;  // abbe's
  std::vector<FileFingerprint> files;
  std::string model;           // e.g. "ae-arm"
  std::string overlay_time_s;  // campaign time of the overlay's terms; empty: no overlay
  double tol_um = 0.0, step_mm = 0.0, min_segment_mm = 0.0;
  bool spread_takeups = false;
  std::vector<std::string> setup;  // one line each: offsets, tools, start point
  std::string date;                // UTC, ISO 8601
  std::size_t line = 0;            // read_provenance: line of the marker
};

// The machine YAML and its component table, each with the SHA-256 of its bytes.
std::vector<FileFingerprint> machine_fingerprints(const machine::Machine& machine);
FileFingerprint file_fingerprint(const std::string& role, const std::string& path);

// What the interpreter assumes about the machine's setup, in words.
std::vector<std::string> setup_lines(const gcode::InterpreterConfig& config);

struct CompensateOptions;
// Everything of a compensate run: the machine's files (and the overlay's,
// when `overlay` is not empty), model, tol, step and setup, dated now.
Provenance make_provenance(const std::string& version, const machine::Machine& machine,
                           const gcode::InterpreterConfig& config, const std::string& model,
                           const std::string& overlay, double overlay_time_s,
                           const CompensateOptions& options);

// The comment lines, each ending with `eol`.
std::string format_provenance(const Provenance& p, std::string_view eol);

bool carries_provenance(std::string_view line);

// Reads the block at the top of a program (after a leading "%" and an O
// number line); nullopt if the program does not start with one. Leaves the
// stream at an unspecified position.
std::optional<Provenance> read_provenance(std::istream& in);

// Throws abbe::InputError (at the block's line in `file`) if a machine file
// the block names differs in content from the one in `current`.
void check_machine_files(const Provenance& p, const std::string& file,
                         const std::vector<FileFingerprint>& current);

// Throws abbe::InputError if a setup line of the block (same subject: the
// text before ':') differs from the one of `current` (setup_lines()).
void check_setup(const Provenance& p, const std::string& file,
                 const std::vector<std::string>& current);

}  // namespace abbe::compensate
