#pragma once
// Interpreter: modal state (units, distance mode, plane, arc centre mode,
// work offsets, G92, tool length, canned cycles, feed/spindle/tool) → Motions.
// Refuses what it does not support with an InputError naming the construct.
#include <array>
#include <functional>
#include <map>
#include <memory>
#include <string>

#include <Eigen/Core>

#include "abbe/gcode/block.hpp"
#include "abbe/gcode/motion.hpp"

namespace abbe::gcode {

struct InterpreterConfig {
  std::array<Eigen::Vector3d, 6> work_offsets{  // G54..G59, mm
      Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero(),
      Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero()};
  std::map<int, double> tool_lengths;  // H number -> tool length, mm (G43 H)
  // Length of the tool in the spindle when no G43 is active (the program then
  // drives the spindle nose s directly and P = s - L·e_z), mm.
  double default_tool_length = 0.0;
  Eigen::Vector3d initial_position = Eigen::Vector3d::Zero();  // tool tip at program start, mm
};

using MotionSink = std::function<void(const Motion&)>;

class Interpreter {
 public:
  Interpreter(InterpreterConfig config, std::string file);
  ~Interpreter();
  Interpreter(Interpreter&&) noexcept;
  Interpreter& operator=(Interpreter&&) noexcept;

  // Executes one block; every motion it makes goes to `sink` in order.
  // `raw_line` is used for error messages (caret display). Throws InputError.
  void execute(const Block& block, const std::string& raw_line, const MotionSink& sink);

  bool program_ended() const;  // M2 / M30 seen
  Eigen::Vector3d position() const;  // current tool tip, mm

 private:
  struct State;
  std::unique_ptr<State> state_;
};

}  // namespace abbe::gcode
