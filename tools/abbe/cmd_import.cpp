// abbe import: converts third-party measurement reports into abbe's files
// (docs/formats.md): plugplate (SDSS plug-plate CMM reports) and ballbar
// (ISO 230-4 circular tests) into measured-data CSV; laser (laser-calibration
// exports) into the ISO 230-2 runs file and component-table rows.
#include <memory>
#include <string>
#include <vector>

#include "abbe/io/atomic_file.hpp"
#include "abbe/io/ballbar.hpp"
#include "abbe/io/laser_export.hpp"
#include "abbe/io/measured_data.hpp"
#include "abbe/io/plugplate.hpp"
#include "command.hpp"

namespace abbe::cli {
namespace {

struct ImportOptions {
  std::string format;
  std::string input;
  std::string output = "-";
  std::string table;  // laser: also the component-table rows
};

// laser: a laser-calibration export (one or more components) -> the ISO
// 230-2 runs file (and --table).
int run_import_laser(const ImportOptions& o) {
  const std::vector<io::LaserExport> data = io::load_laser_exports(o.input);
  if (!o.table.empty()) io::write_file_atomically(o.table, io::laser_table_csv(data));
  io::write_file_atomically(o.output, io::laser_runs_csv(data));
  return kOk;
}

int run_import(const ImportOptions& o) {
  if (o.format == "laser") return run_import_laser(o);
  const io::MeasuredData data =
      o.format == "ballbar" ? io::load_ballbar(o.input) : io::load_plugplate(o.input);
  io::AtomicOutputFile out(o.output);
  const std::string body = io::measured_data_to_csv(data);
  out.write(body.data(), body.size());
  out.commit();
  return kOk;
}

const CommandRegistrar registrar(
    "import", "Convert a measurement report into abbe's files (formats: plugplate, ballbar, laser)",
    75, [](CLI::App& sub, const GlobalOptions&) -> CommandAction {
      auto o = std::make_shared<ImportOptions>();
      sub.footer("Example: abbe import plugplate PLATE_REPORT.txt -o measured.csv");
      sub.add_option("format", o->format,
                     "Report format: plugplate (SDSS plug-plate CMM report), ballbar (ISO "
                     "230-4 circular test CSV) -> measured data; laser (laser-calibration "
                     "export) -> ISO 230-2 runs file")
          ->required()
          ->check(CLI::IsMember({"plugplate", "ballbar", "laser"}));
      sub.add_option("input", o->input, "The report file (- for stdin)")->required();
      sub.add_option("-o,--output", o->output, "Measured-data CSV (written atomically), - stdout")
          ->capture_default_str();
      sub.add_option("--table", o->table,
                     "laser: also write the component-table rows (mean and s/√n per target)");
      return [o] { return run_import(*o); };
    });

}  // namespace
}  // namespace abbe::cli
