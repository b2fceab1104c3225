#pragma once
// LaserExport: the CSV a laser-calibration software exports for one
// component of one axis (a file may hold several, one section each) — `#` metadata lines (axis,
// component, units, reference, environment compensation) and the columns target, run, direction,
// reading in any order (docs/formats.md, "Laser calibration export"). Read with the one CSV reader;
// the readings are converted to µm (linear components) or µrad (angular ones) after checking that
// the unit fits the component; written as the ISO 230-2 runs file that `abbe iso230` reads, and as
// rows of the component table (mean per target and direction, with its standard uncertainty s/√n).
// `abbe import laser`.
#include <cstddef>
#include <istream>
#include <optional>
#include <string>
#include <vector>

namespace abbe::io {

enum class LaserUnit { um, mm, arcsec, urad, mm_per_m };

// The unit of a `# units:` value: µm, um, mm, arcsec, arc-sec, ", µrad,
// urad, mm/m (case-insensitive); nullopt for anything else.
std::optional<LaserUnit> parse_laser_unit(const std::string& text);
bool is_angular(LaserUnit unit);
// The factor to µm (linear units) or µrad (angular units): 1 arcsec =
// π/648000 rad = 4.8481368… µrad, 1 mm/m = 1000 µrad, 1 mm = 1000 µm.
double laser_unit_factor(LaserUnit unit);

struct LaserReading {
  double target_mm = 0.0;
  int run = 1;
  int dir = +1;        // +1 up (approached moving +), −1 down
  double value = 0.0;  // converted: µm or µrad
  std::size_t line = 0;
};

struct LaserExport {
  std::string file;
  char axis = 'X';
  std::string component;  // ISO 230-1 name, e.g. "EXX", "EBX"
  bool angular = false;
  LaserUnit unit = LaserUnit::um;
  std::string unit_text;                 // as written
  std::optional<double> reference_mm;    // `# reference:` (a target), when given
  std::string environment_compensation;  // "automatic", "manual", "off" or "" (not given)
  std::vector<LaserReading> readings;    // in file order
};

// Reads and checks the export; throws abbe::InputError naming the file, the
// line, the column and the field of the first problem (a missing metadata
// line: the file and the field).
LaserExport read_laser_export(std::istream& in, const std::string& file);
LaserExport load_laser_export(const std::string& path);  // "-": stdin

// A file with one or more sections, one component each: a section is its
// metadata lines, its header line and its readings; a metadata line
// (`# axis:`, `# component:`, …) after readings starts the next section.
// Every section is read and checked as a file of its own (units per
// component), with the line numbers of the whole file; two sections of the
// same component are refused (field "component", at the second one).
std::vector<LaserExport> read_laser_exports(std::istream& in, const std::string& file);
std::vector<LaserExport> load_laser_exports(const std::string& path);  // "-": stdin

// The ISO 230-2 runs CSV (docs/formats.md, "ISO 230-2 runs"):
// axis,component,target_mm,run,direction,deviation (µm or µrad, up/down).
std::string laser_runs_csv(const LaserExport& data);
// The sections one after another under one header.
std::string laser_runs_csv(const std::vector<LaserExport>& sections);

// Component-table rows with the `uncertainty` column (docs/formats.md): per
// target (ascending) the mean over the runs and s/√n, as fwd and rev series
// when both directions were measured, else as one mean series. Throws
// abbe::InputError (field "run") when a target has fewer than 2 runs of a
// direction (no repeatability).
std::string laser_table_csv(const LaserExport& data);
std::string laser_table_csv(const std::vector<LaserExport>& sections);

}  // namespace abbe::io
