// abbe import: converts third-party measurement reports into measured-data
// CSV (docs/formats.md). Formats: plugplate (SDSS plug-plate CMM reports).
#include <memory>
#include <string>

#include "abbe/io/atomic_file.hpp"
#include "abbe/io/ballbar.hpp"
#include "abbe/io/measured_data.hpp"
#include "abbe/io/plugplate.hpp"
#include "command.hpp"

namespace abbe::cli {
namespace {

struct ImportOptions {
  std::string format;
  std::string input;
  std::string output = "-";
};

int run_import(const ImportOptions& o) {
  const io::MeasuredData data =
      o.format == "ballbar" ? io::load_ballbar(o.input) : io::load_plugplate(o.input);
  io::AtomicOutputFile out(o.output);
  const std::string body = io::measured_data_to_csv(data);
  out.write(body.data(), body.size());
  out.commit();
  return kOk;
}

const CommandRegistrar registrar(
    "import", "Convert a measurement report into measured-data CSV (formats: plugplate)", 75,
    [](CLI::App& sub, const GlobalOptions&) -> CommandAction {
      auto o = std::make_shared<ImportOptions>();
      sub.footer("Example: abbe import plugplate PLATE_REPORT.txt -o measured.csv");
      sub.add_option("format", o->format,
                     "Report format: plugplate, ballbar (ISO 230-4 circular test CSV)")
          ->required()
          ->check(CLI::IsMember({"plugplate", "ballbar"}));
      sub.add_option("input", o->input, "The report file (- for stdin)")->required();
      sub.add_option("-o,--output", o->output, "Measured-data CSV (written atomically), - stdout")
          ->capture_default_str();
      return [o] { return run_import(*o); };
    });

}  // namespace
}  // namespace abbe::cli
