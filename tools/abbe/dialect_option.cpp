#include "dialect_option.hpp"

#include <string>

namespace abbe::cli {

void add_dialect_options(CLI::App& sub, gcode::DialectOptions& dialect) {
  sub.add_option_function<std::string>(
         "--dialect",
         [&dialect](const std::string& name) { dialect.dialect = *gcode::dialect_from_name(name); },
         "How the program is written: linuxcnc (RS274/NGC as LinuxCNC reads it) or "
         "fanuc (Fanuc/Haas posts: O-numbered programs with M98 P L / M99 "
         "subprograms in the same file, lengths without a decimal point in least "
         "increments, G04 P in ms, cycle repeats K; the look-ahead and smoothing codes "
         "G05 G05.1 G08 G103 G187 and the M29 rigid-tapping mode are carried, not "
         "motion; G28 G91 Z0., G53, G84, G95 are read as in LinuxCNC; G68 rotation, G51 "
         "scaling, G54.1/G154 and macro calls are refused by name; docs/fanuc.md)")
      ->check(CLI::IsMember({"linuxcnc", "fanuc"}))
      ->default_str("linuxcnc");
  sub.add_option_function<std::string>(
         "--integers",
         [&dialect](const std::string& name) {
           dialect.integers = *gcode::integer_numbers_from_name(name);
         },
         "fanuc: a length written without a decimal point (X100) counts least "
         "increments of 0.001 mm / 0.0001 in (increment, Fanuc's default) or whole "
         "mm / in (units, calculator-type input)")
      ->check(CLI::IsMember({"increment", "units"}))
      ->default_str("increment");
  sub.add_option("--var-file", dialect.var_file,
                 "linuxcnc: rs274's parameter file (lines 'number value'), read before the "
                 "program runs")
      ->check(CLI::ExistingFile);
  sub.add_option("--subroutine-path", dialect.subroutine_path,
                 "linuxcnc: folder searched for name.ngc (holding 'o<name> sub') when "
                 "'o<name> call' finds no such subroutine in the program")
      ->check(CLI::ExistingDirectory);
  sub.add_option("--loop-limit", dialect.loop_limit,
                 "linuxcnc: loop iterations (while, do, repeat; all loops together) after "
                 "which a program is refused as a runaway loop")
      ->capture_default_str();
}

}  // namespace abbe::cli
