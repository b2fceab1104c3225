#pragma once
// Canned cycles in compensate (docs/compensation.md, "Canned cycles"): one
// block drills one hole (or L holes in G91), and its words — the hole
// position in the plane and the depth along the drill axis — carry the
// correction at the hole's bottom; the clearance moves keep their nominal
// levels. The corrector keeps the state a series of cycles shares (the
// correction at the initial level, the depth word in force) and edits the
// block through the host, the compensator that owns the block's text.
#include <Eigen/Core>
#include <cstddef>
#include <string>
#include <vector>

#include "abbe/compensate/number_format.hpp"
#include "abbe/compensate/program_compensator.hpp"
#include "abbe/gcode/block.hpp"
#include "abbe/gcode/motion.hpp"
#include "abbe/path/path_point.hpp"
#include "block_editor.hpp"

namespace abbe::compensate::detail {

// What the compensator offers the cycle corrector for one block.
class CycleHost {
 public:
  // The correction (commanded − nominal tool tip, mm) at a fragment point.
  virtual Eigen::Vector3d solve(const path::PathPoint& point) = 0;
  // Program-frame coordinates (program units) of a tool-tip point of the block.
  virtual Eigen::Vector3d prog(const Eigen::Vector3d& tip) const = 0;
  // Sets axis word `letter` so that the absolute program value is
  // `target_abs` (an increment from `reference` in G91); returns the value in effect.
  virtual double set_abs(BlockEditor& editor, char letter, double target_abs, double reference,
                         double baseline_abs, bool incremental, bool may_insert) = 0;
  virtual void warn(std::size_t line, const std::string& text) = 0;

 protected:
  ~CycleHost() = default;
};

// One block that made a canned cycle's motions, as the compensator sees it.
struct CycleBlock {
  const gcode::Block& block;  // as the interpreter read it (RS274/NGC form)
  const std::vector<gcode::Motion>& motions;
  const std::vector<std::vector<path::PathPoint>>& points;  // fragment points per motion
  gcode::Plane plane = gcode::Plane::xy;
  bool retract_to_r = true;  // G99 (false: G98)
  bool incremental = false;  // G91
  double unit = 1.0;         // mm per program unit
  int decimals = 4;
  const NumberStyle& plain;                             // of the words written anew
  Eigen::Vector3d tip_after = Eigen::Vector3d::Zero();  // tool tip after the block, mm
  Eigen::Vector3d delta = Eigen::Vector3d::Zero();      // correction in force before it, mm
};

class CycleCorrector {
 public:
  // Edits the cycle block's words (and may add lines to `pieces`, G91 with
  // L repeats) so that the hole bottom carries its correction; `cmd` is the
  // commanded point (program frame and units), updated. Afterwards `cmd`
  // stands at the clearance level with the correction that level keeps.
  void correct(const CycleBlock& c, CycleHost& host, BlockEditor& editor,
               std::vector<std::string>& pieces, Eigen::Vector3d& cmd, CompensateSummary& summary);
  // A block that is no cycle (G80, or a single motion) ends the series.
  void end_series() { in_series_ = false; }

 private:
  void repeated(const CycleBlock& c, CycleHost& host, BlockEditor& editor,
                std::vector<std::string>& pieces, Eigen::Vector3d& cmd, int repeats, double level,
                CompensateSummary& summary);

  // G91 canned cycles: their R is relative to the initial level, the height
  // where the series began, which carries that point's correction along the
  // drill axis (mm); the depth word takes it out.
  bool in_series_ = false;
  double initial_level_delta_ = 0.0;
  double depth_delta_ = 0.0;    // correction in the modal depth word, mm
  double written_depth_ = 0.0;  // the modal depth word of the original (program units)
};

}  // namespace abbe::compensate::detail
