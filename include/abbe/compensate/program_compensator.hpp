#pragma once
// compensate_program: rewrites an NC program so that the predicted path of
// the rewritten program is the nominal path of the original (docs/compensation.md).
// Streams block by block: parse → interpret → fragment → solve each
// fragment point (PointSolver) → replace exactly the numbers of the corrected
// coordinates in the raw line; every other byte is kept. Straight feeds and
// arcs whose correction is not linear along them within tol/2 are split into
// pieces (lines: G1 pieces; single-turn arcs: arc pieces, which keep the
// modal motion code); rapids get their written end coordinates corrected;
// canned cycles their hole position and depth.
#include <array>
#include <cstddef>
#include <functional>
#include <istream>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "abbe/compensate/point_solver.hpp"
#include "abbe/compensate/provenance.hpp"
#include "abbe/gcode/interpreter.hpp"
#include "abbe/machine/machine.hpp"
#include "abbe/model/error_model.hpp"

namespace abbe::compensate {

struct CompensateOptions {
  double tol_um = 1.0;  // allowed predicted deviation from the nominal path
  double step = 5.0;    // fragment step, mm
  int decimals = -1;    // max decimals of a corrected number; −1: 4 (mm) / 5 (inch)
  // The machine's travel: a nominal point whose axis positions lie outside
  // is refused (InputError at its line) unless allow_outside_travel; then
  // it is counted. Empty: not checked.
  std::optional<std::array<machine::Travel, 3>> travel;
  bool allow_outside_travel = false;
  // No inserted piece shorter than this, mm (commanded length). A reversal
  // jump shorter than it and within tol is taken up along the first
  // min_segment + 2|jump| of the move instead of by a micro move of its own;
  // a larger one keeps its micro move (tol first) unless spread_takeups.
  // 0: exact micro moves for every jump.
  double min_segment = 0.01;
  bool spread_takeups = false;
  bool renumber = false;  // give inserted pieces N numbers (previous N + piece index)
  // Compensate holds the path points of one block in memory: a block whose
  // motions need more points than this at `step` (a canned cycle with a large
  // L, a typo in a coordinate) is refused at its line rather than exhausting
  // memory.
  std::size_t max_block_points = 1'000'000;
  // Written as comment lines at the top of the output (compensate/provenance.hpp).
  std::optional<Provenance> provenance;
  SolverOptions solver;
};

struct CompensateSummary {
  std::size_t lines = 0;
  std::size_t blocks_changed = 0;
  std::size_t pieces_inserted = 0;  // every inserted line (pieces and take-up moves)
  std::size_t takeup_moves = 0;    // inserted micro moves taking up a reversal jump ≥ min_segment
  std::size_t takeups_spread = 0;  // reversal jumps < min_segment taken up along the move
  double max_takeup_um = 0.0;      // largest of those jumps, µm
  double max_takeup_length_mm = 0.0;   // longest stretch over which one was taken up
  std::size_t short_pieces_kept = 0;   // pieces < min_segment kept because merging broke tol
  std::size_t short_takeup_moves = 0;  // moves abbe wrote shorter than min_segment
  // Shortest move abbe wrote (inserted lines and blocks turned into take-up
  // moves), mm; 0 when none. min_segment_mm: the option in force.
  double shortest_inserted_mm = std::numeric_limits<double>::infinity();
  double min_segment_mm = 0.0;
  std::size_t motion_blocks = 0;        // blocks that make at least one motion
  std::size_t points = 0;               // solved points
  double max_correction_um = 0.0;       // max |c − n|
  std::size_t out_of_range_points = 0;  // points with a lookup outside the tables
  std::size_t unconverged_points = 0;
  std::vector<std::size_t> unconverged_lines;  // first 20
  std::size_t arcs_split_turns = 0;      // multi-turn arcs split into pieces (their P word removed)
  std::size_t uncompensated_blocks = 0;  // G91 canned cycles whose holes could not be found
  std::size_t shared_increment_blocks = 0;  // G91 G99 cycles with L: one increment for all holes
  std::vector<std::string> warnings;        // first 20, "file:line: text"
  std::size_t outside_travel_points = 0;    // with allow_outside_travel
  std::string travel_text;                  // machine::TravelCheck::text()
};

using TextSink = std::function<void(const char* data, std::size_t size)>;

// The summary's lines on inserted moves and segment lengths ("  ..." lines).
std::string segment_text(const CompensateSummary& s);

// Throws abbe::InputError for what the front end refuses (same message) and
// for a point outside the tables under the `error` policy.
CompensateSummary compensate_program(std::istream& in, const std::string& file,
                                     const gcode::InterpreterConfig& config,
                                     const model::ErrorModel& model,
                                     const CompensateOptions& options, const TextSink& out);

}  // namespace abbe::compensate
