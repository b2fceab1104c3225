#pragma once
// Interpreter: modal state (units, distance mode, plane, arc centre mode,
// work offsets, G92, tool length, canned cycles, feed/spindle/tool) → Motions.
// Refuses what it does not support with an InputError naming the construct.
//
// Semantics are LinuxCNC 2.9's rs274ngc (checked against its standalone
// rs274, docs/interop.md): start-up modes G17 G21 G90 G91.1 G94 G54 G49 G80
// G99 G64; the order of execution within a block (G93/G94/G95, F, S, T, M6,
// M3-M5, G4, plane, units, G43/G49, G54.., G61/G64, distance modes, G98/G99,
// G10/G28/G30/G52/G92.., motion, M0/M2/M30); a motion code without axis
// words makes a zero-length move; canned cycles G73 G74 G81-G86 G89 in all
// three planes, with the G98 level kept for a series of cycles. Supported:
// G0-G3 (IJK, R, P turns, helices), G4, G10 L1/L2/L10/L20, G17-G19,
// G20/G21, G28/G28.1/G30/G30.1 (through the intermediate point to the
// stored position, InterpreterConfig::g28_position), G40/G41/G42/G41.1/G42.1
// (cutter radius compensation in G17 as rs274ngc: entry move, inside and
// outside corners of lines and arcs), G43/G43.1/G49, G52,
// G53, G54-G59, G61/G61.1/G64 (carried in ModalState), G80, G90/G91,
// G90.1/G91.1, G92/G92.1/G92.2/G92.3, G93/G94/G95 (Motion::feed follows),
// G97, G98/G99; M0 M1 M2 M3 M4 M5 M6 M7 M8 M9 M30 M48-M53 (carried) M60
// M61 M70-M73; polar words @ ^ on motions; rotary words A B C whose axis
// does not move (one warning). A program whose first line
// is '%' ends at the next '%'. Everything else is refused. A program in the
// Fanuc/Haas dialect (InterpreterConfig::dialect) is read through an adapter
// that turns each block into its RS274/NGC equivalent (docs/fanuc.md).
#include <Eigen/Core>
#include <array>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <string_view>

#include "abbe/gcode/block.hpp"
#include "abbe/gcode/dialect.hpp"
#include "abbe/gcode/modal_state.hpp"
#include "abbe/gcode/motion.hpp"

namespace abbe::gcode {

namespace detail {
struct ExecState;  // the modal state with its configuration (src/gcode)
}  // namespace detail

struct InterpreterConfig {
  std::array<Eigen::Vector3d, 6> work_offsets{// G54..G59, mm
                                              Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero(),
                                              Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero(),
                                              Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero()};
  std::map<int, double> tool_lengths;  // H number -> tool length, mm (G43 H)
  // Tool number -> cutter diameter, mm: the radius of G41/G42 (D word or
  // the tool in the spindle). G41.1/G42.1 take the diameter from D instead.
  std::map<int, double> tool_diameters;
  // Length of the tool in the spindle when no G43 is active (the program then
  // drives the spindle nose s directly and P = s - L·e_z), mm.
  double default_tool_length = 0.0;
  Eigen::Vector3d initial_position = Eigen::Vector3d::Zero();  // tool tip at program start, mm
  // Stored positions of G28 and G30: machine coordinates of the spindle nose
  // (s = P + L·e_z), mm. LinuxCNC keeps them in parameters 5161-5163 and
  // 5181-5183; the default is the machine home (0, 0, 0).
  Eigen::Vector3d g28_position = Eigen::Vector3d::Zero();
  Eigen::Vector3d g30_position = Eigen::Vector3d::Zero();
  // G43 with a tool that has no length in tool_lengths: an error (predict,
  // compensate: the model needs L) or, when true, accepted with one warning
  // (path, interpret: the tool-tip path does not depend on L; Motion::
  // tool_length is then NaN, "unknown").
  bool allow_unknown_tool_length = false;
  DialectOptions dialect;  // LinuxCNC (default) or Fanuc/Haas (gcode/dialect.hpp)
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
  void execute(const Block& block, std::string_view raw_line, const MotionSink& sink);

  // The same for a block whose parameters and expressions the caller has
  // evaluated into its words (gcode::run_program does). execute() refuses a
  // block with parameters, expressions or an O-word: a caller that goes
  // line by line (compensate, verify) cannot follow them.
  void execute_evaluated(const Block& block, std::string_view raw_line, const MotionSink& sink);

  // Subroutine call levels (gcode::run_program calls them at o<name> call
  // and at its return/endsub): M70/M72/M71 save, restore and invalidate the
  // modal state of the current level; M73 saves it and the return restores
  // it (rs274ngc). `line`, `raw_line`: the return's line, for errors.
  void enter_call();
  void leave_call(std::size_t line, std::string_view raw_line);

  // The end of the program: motions that cutter radius compensation still
  // holds back (it waits for the next move to place a corner) go to `sink`.
  void finish(const MotionSink& sink);

  // The last executed block as the interpreter read it: the caller's block,
  // or its RS274/NGC form for a program in another dialect (numbers in
  // program units, offsets still into the caller's line). A post-processor
  // decides on this what to rewrite. Valid until the next execute().
  const Block& block_read() const;
  // The group-0 code of that block (gcode_id: G4 G10 G28 G30 G52 G53 G92 …),
  // -1 when it has none.
  int non_modal_read() const;

  bool program_ended() const;             // M2 / M30 seen
  std::size_t motions_delivered() const;  // motions handed to the sinks so far
  Eigen::Vector3d position() const;       // current tool tip, mm

  // Modal state after the last executed block (for post-processors that
  // write coordinates back in the program's own frame and units).
  const ModalState& modal() const;
  bool inch() const;                         // G20
  bool incremental() const;                  // G91
  bool arc_centre_absolute() const;          // G90.1
  Plane plane() const;                       // G17/G18/G19
  bool retract_to_r() const;                 // G99 (false: G98) for canned cycles
  Eigen::Vector3d program_position() const;  // current point in the program frame, program units

  // LinuxCNC's read-only predefined named parameters that mirror the state
  // after the last block (#<_x>, #<_abs_z>, #<_motion_mode>, #<_ccomp>,
  // #<_metric>, …; `name` in rs274ngc's form: lower case, with the leading
  // '_'). nullopt for any other name. predefined_parameters.cpp lists them.
  std::optional<double> predefined_parameter(const std::string& name) const;

 private:
  std::unique_ptr<detail::ExecState> state_;
};

}  // namespace abbe::gcode
