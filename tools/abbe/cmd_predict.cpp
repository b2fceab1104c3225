// abbe predict: the predicted deviation of the tool tip along an NC program
// (parse → interpret → fragment → error model, block by block) or at the
// points of a CSV file (a CMM or laser grid), for one error model or all
// three side by side. Output is streamed; a summary per model goes to stderr
// (stdout when -o names a file).
#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <cstring>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "abbe/diagnose/overlay_extension.hpp"
#include "abbe/gcode/program.hpp"
#include "abbe/io/atomic_file.hpp"
#include "abbe/io/csv_fields.hpp"
#include "abbe/io/input_error.hpp"
#include "abbe/io/path_writer.hpp"
#include "abbe/io/progress.hpp"
#include "abbe/io/row_text.hpp"
#include "abbe/machine/interpreter_setup.hpp"
#include "abbe/machine/machine.hpp"
#include "abbe/model/error_model.hpp"
#include "abbe/path/fragmenter.hpp"
#include "command.hpp"
#include "input_stream.hpp"

namespace abbe::cli {
namespace {

struct PredictOptions {
  std::string input;
  std::string machine;
  std::string model = "ae-arm";
  std::string output = "-";
  std::string format = "csv";
  std::string summary_json;
  std::string extend;  // overlay of effects found by `abbe diagnose` (docs/formats.md)
  double step = 5.0;
  double rapid_rate = 10000.0;
  bool points = false;  // input is a CSV of points even without the .csv extension
  bool summary_only = false;
};

// Running statistics of one model over all points.
struct ModelStats {
  std::size_t points = 0;
  Eigen::Vector3d max_abs = Eigen::Vector3d::Zero();  // µm
  double sum_d2 = 0.0;                                // µm²
  double max_d = 0.0;                                 // µm
  void add(const Eigen::Vector3d& e, double d) {      // d = |e|
    ++points;
    max_abs = max_abs.cwiseMax(e.cwiseAbs());
    sum_d2 += d * d;
    max_d = std::max(max_d, d);
  }
  double rms() const { return points ? std::sqrt(sum_d2 / static_cast<double>(points)) : 0.0; }
};

// Suffix of the per-model columns in `--model all` output.
std::string column_suffix(model::ModelKind k) {
  return k == model::ModelKind::ae_arm ? "ae_arm" : model::to_string(k);
}

// Reads a CSV of points: header with x, y, z and optional vx, vy, vz and
// tool_length (other columns, e.g. the measured deviations, are ignored).
class PointReader {
 public:
  PointReader(std::istream& in, std::string file, double default_tool_length)
      : in_(in), file_(std::move(file)), default_l_(default_tool_length) {
    if (!next_line())
      throw InputError({file_, 1, 1, "header", ""}, "empty points file: a header is required");
    auto names = io::split_csv_line(line_);
    for (std::size_t i = 0; i < names.size(); ++i) {
      std::string_view n = io::trim_blanks(names[i].text);
      for (std::size_t k = 0; k < kNames.size(); ++k)
        if (n == kNames[k]) {
          if (col_[k] >= 0)
            error(names[i].column, std::string(n), fmt::format("column `{}` appears twice", n));
          col_[k] = static_cast<int>(i);
        }
    }
    for (std::size_t k = 0; k < 3; ++k)
      if (col_[k] < 0)
        error(1, "header",
              fmt::format("the header has no `{}` column (x, y, z are required)", kNames[k]));
  }

  bool next(model::EvalPoint& p, std::size_t& line) {
    while (next_line()) {
      if (io::trim_blanks(line_).empty()) continue;
      auto fields = io::split_csv_line(line_);
      auto get = [&](std::size_t k) -> std::optional<double> {
        if (col_[k] < 0) return std::nullopt;
        auto c = static_cast<std::size_t>(col_[k]);
        if (c >= fields.size())
          error(line_.size() + 1, std::string(kNames[k]),
                fmt::format("{} fields, but `{}` is column {}", fields.size(), kNames[k], c + 1));
        std::string_view t = io::trim_blanks(fields[c].text);
        if (t.empty()) {
          if (k < 3) error(fields[c].column, std::string(kNames[k]), "empty coordinate");
          return std::nullopt;
        }
        double v = 0.0;
        const char* b = t.data();
        if (*b == '+') ++b;
        auto [ptr, ec] = std::from_chars(b, t.data() + t.size(), v);
        if (ec != std::errc() || ptr != t.data() + t.size() || !std::isfinite(v))
          error(fields[c].column, std::string(kNames[k]),
                fmt::format("\"{}\" is not a finite number", t));
        return v;
      };
      for (std::size_t k = 0; k < 3; ++k) p.p[static_cast<Eigen::Index>(k)] = *get(k);
      for (std::size_t k = 0; k < 3; ++k) {
        auto v = get(3 + k);
        if (v && *v != -1.0 && *v != 0.0 && *v != 1.0)
          error(fields[static_cast<std::size_t>(col_[3 + k])].column, std::string(kNames[3 + k]),
                "the direction of motion must be -1, 0 or 1");
        p.dir[k] = static_cast<std::int8_t>(v ? *v : 0.0);
      }
      auto l = get(6);
      p.tool_length = l ? *l : default_l_;
      p.time = 0.0;
      line = line_no_;
      return true;
    }
    return false;
  }

 private:
  static constexpr std::array<std::string_view, 7> kNames{"x",  "y",  "z",          "vx",
                                                          "vy", "vz", "tool_length"};
  bool next_line() {
    if (!std::getline(in_, line_)) return false;
    ++line_no_;
    return true;
  }
  [[noreturn]] void error(std::size_t column, const std::string& field, const std::string& msg) {
    throw InputError({file_, line_no_, column, field, line_}, msg);
  }

  std::istream& in_;
  std::string file_;
  double default_l_;
  std::string line_;
  std::size_t line_no_ = 0;
  std::array<int, 7> col_{-1, -1, -1, -1, -1, -1, -1};
};

// Formats the per-point output into a buffer handed to the file in chunks.
// A row whose numbers are all ordinary (io::fixed6_fits) is formatted in
// place at the end of the buffer with io::write_fixed6 (no copy, no
// allocation, no format string); a row with a huge or non-finite number goes
// through io::append_fixed6. The line number text is kept while it repeats
// (every point of a motion has the same line).
class PredictionWriter {
 public:
  PredictionWriter(io::PathFormat format, std::vector<model::ModelKind> kinds, io::ByteSink sink)
      : format_(format), kinds_(std::move(kinds)), sink_(std::move(sink)) {
    for (auto k : kinds_) {
      json_keys_.push_back(fmt::format(", \"{}\": {{\"px\": ", model::to_string(k)));
      row_max_ += 16 * (io::kFixed6MaxChars + 8) + json_keys_.back().size();
    }
    pred_.resize(kinds_.size());
    buf_.reserve(kChunk + row_max_);
    const bool all = kinds_.size() > 1;
    if (format_ == io::PathFormat::csv) {
      std::string header = all ? "x,y,z,line" : "x,y,z,px,py,pz,dx,dy,dz,d";
      for (auto k : kinds_) {
        std::string s = all ? "_" + column_suffix(k) : "";
        if (all) header += fmt::format(",px{0},py{0},pz{0},dx{0},dy{0},dz{0},d{0}", s);
        if (k == model::ModelKind::dual) header += fmt::format(",dx2{0},dy2{0},dz2{0}", s);
      }
      if (!all) header += ",line";
      put(header + "\n");
    } else {
      put("{\"points\": [\n");
    }
  }

  // norms[i] = |devs[i].e_um|.
  void write(const model::EvalPoint& p, std::size_t line, const std::vector<model::Deviation>& devs,
             const std::vector<double>& norms) {
    if (line != line_ || line_size_ == 0) {
      line_ = line;
      line_size_ = static_cast<std::size_t>(
          io::write_decimal(line_text_.data(), static_cast<unsigned long long>(line)) -
          line_text_.data());
    }
    // The in-place formatter takes the row when every number fits; the sum of
    // the magnitudes of the nominal point and the deviations bounds every
    // number of the row (|p + 1e-3·e| and |e| are at most that sum), so it is
    // a cheap sufficient test (NaN and infinity fail it, and a row that fails
    // takes the appending path, which writes the same text).
    double magnitude = l1(p.p);
    for (std::size_t i = 0; i < kinds_.size(); ++i) {
      const model::Deviation& d = devs[i];
      pred_[i] = p.p + 1e-3 * d.e_um;
      magnitude += l1(d.e_um) + l1(d.second_order_um);
    }
    const bool fits = io::fixed6_fits(magnitude);
    if (fits) {
      const std::size_t old_size = buf_.size();
      buf_.resize(old_size + row_max_);
      io::InPlaceRow out{buf_.data() + old_size};
      row(out, p, devs, norms);
      buf_.resize(static_cast<std::size_t>(out.p - buf_.data()));
    } else {
      io::AppendedRow out{buf_};
      row(out, p, devs, norms);
    }
    ++points_;
    if (buf_.size() >= kChunk) flush();
  }

  void finish(const nlohmann::json& summary) {
    if (format_ == io::PathFormat::json) put("\n],\n\"summary\": " + summary.dump(2) + "}\n");
    flush();
  }

 private:
  static constexpr std::size_t kChunk = std::size_t{1} << 16;

  template <class Out>
  void row(Out& out, const model::EvalPoint& p, const std::vector<model::Deviation>& devs,
           const std::vector<double>& norms) const {
    const bool all = kinds_.size() > 1;
    if (format_ == io::PathFormat::csv) {
      num3(out, p.p, "", ",", ",");
      if (all) {
        out.ch(',');
        out.block(line_text_, line_size_);
      }
      for (std::size_t i = 0; i < kinds_.size(); ++i) {
        const model::Deviation& d = devs[i];
        const Eigen::Vector3d& e = d.e_um;
        num3(out, pred_[i], ",", ",", ",");
        num3(out, e, ",", ",", ",");
        out.ch(',');
        out.num(norms[i]);
        if (kinds_[i] == model::ModelKind::dual) num3(out, d.second_order_um, ",", ",", ",");
      }
      if (!all) {
        out.ch(',');
        out.block(line_text_, line_size_);
      }
      out.ch('\n');
    } else {
      out.text(points_ ? ",\n{\"x\": " : "{\"x\": ");
      num3(out, p.p, "", ", \"y\": ", ", \"z\": ");
      out.text(", \"line\": ");
      out.block(line_text_, line_size_);
      for (std::size_t i = 0; i < kinds_.size(); ++i) {
        const model::Deviation& d = devs[i];
        const Eigen::Vector3d& e = d.e_um;
        out.text(json_keys_[i]);
        num3(out, pred_[i], "", ", \"py\": ", ", \"pz\": ");
        num3(out, e, ", \"dx\": ", ", \"dy\": ", ", \"dz\": ");
        out.text(", \"d\": ");
        out.num(norms[i]);
        if (kinds_[i] == model::ModelKind::dual)
          num3(out, d.second_order_um, ", \"dx2\": ", ", \"dy2\": ", ", \"dz2\": ");
        out.ch('}');
      }
      out.ch('}');
    }
  }
  static double l1(const Eigen::Vector3d& v) {
    return std::abs(v.x()) + std::abs(v.y()) + std::abs(v.z());
  }
  // Three numbers, each after its separator.
  template <class Out, std::size_t N0, std::size_t N1, std::size_t N2>
  static void num3(Out& out, const Eigen::Vector3d& v, const char (&s0)[N0], const char (&s1)[N1],
                   const char (&s2)[N2]) {
    out.text(s0);
    out.num(v.x());
    out.text(s1);
    out.num(v.y());
    out.text(s2);
    out.num(v.z());
  }

  void put(std::string_view s) { buf_.append(s.data(), s.data() + s.size()); }
  void flush() {
    sink_(buf_.data(), buf_.size());
    buf_.clear();
  }

  io::PathFormat format_;
  std::vector<model::ModelKind> kinds_;
  io::ByteSink sink_;
  std::vector<std::string> json_keys_;  // `, "<model>": {"px": ` per model
  std::size_t row_max_ = 192;           // bytes an in-place row may take
  std::vector<Eigen::Vector3d> pred_;   // predicted tool tip per model, mm
  fmt::memory_buffer buf_;
  std::size_t points_ = 0;
  std::array<char, 24> line_text_{};
  std::size_t line_size_ = 0;
  std::size_t line_ = 0;
};

bool ends_with(const std::string& s, const std::string& suffix) {
  return s.size() >= suffix.size() &&
         s.compare(s.size() - suffix.size(), suffix.size(), suffix) == 0;
}

int run_predict(const PredictOptions& o, const GlobalOptions& g) {
  const machine::Machine machine = machine::Machine::load(o.machine);
  std::vector<model::ModelKind> kinds;
  if (o.model == "all") {
    kinds = {model::ModelKind::htm, model::ModelKind::ae_arm, model::ModelKind::dual};
  } else if (auto k = model::parse_model_kind(o.model)) {
    kinds = {*k};
  } else {
    throw InputError({"<command line>", 0, 0, "--model", ""},
                     fmt::format("unknown model \"{}\" (htm, ae-arm, dual or all)", o.model));
  }
  const io::PathFormat format = io::parse_path_format(o.format);
  std::vector<model::ErrorModel> models;
  for (auto k : kinds) models.emplace_back(machine, k);
  // --extend: every model carries the overlay's extra deviation.
  if (!o.extend.empty()) {
    const auto extension = std::make_shared<const diagnose::OverlayExtension>(
        diagnose::Overlay::load(o.extend), machine);
    for (auto& m : models) m = m.with_extension(extension);
  }
  std::vector<model::ModelData> data(kinds.size());
  std::vector<ModelStats> stats(kinds.size());
  std::vector<model::Deviation> devs(kinds.size());
  std::vector<double> norms(kinds.size());  // |e| per model, for the statistics and the output

  InputStream input(o.input, "the input");
  std::istream* in = &input.stream();

  std::unique_ptr<io::AtomicOutputFile> out;
  std::unique_ptr<PredictionWriter> writer;
  if (!o.summary_only) {
    out = std::make_unique<io::AtomicOutputFile>(o.output);
    writer = std::make_unique<PredictionWriter>(
        format, kinds, [&](const char* d, std::size_t n) { out->write(d, n); });
  }

  std::size_t n_points = 0;
  // Progress on a terminal: bytes of the input file read, or points from stdin.
  const bool from_file = !input.from_stdin();
  io::Progress progress("predict", from_file ? io::Progress::file_size(o.input) : 0, !g.quiet,
                        from_file ? "bytes" : "points");
  auto tick = [&] {
    if (!progress.active() || (n_points & 4095) != 0) return;
    if (!from_file) return progress.update(n_points);
    const auto pos = input.position();
    if (pos >= 0) progress.update(static_cast<std::uint64_t>(pos));
  };
  auto evaluate = [&](const model::EvalPoint& p, std::size_t line) {
    for (std::size_t i = 0; i < models.size(); ++i) {
      try {
        devs[i] = models[i].evaluate(p, data[i]);
      } catch (const InputError& e) {
        throw InputError({o.input, line, 0, e.where().field, ""},
                         fmt::format("at the point ({:.4f}, {:.4f}, {:.4f}) mm: {}", p.p.x(),
                                     p.p.y(), p.p.z(), e.message()));
      }
    }
    for (std::size_t i = 0; i < models.size(); ++i) {
      norms[i] = devs[i].e_um.norm();
      stats[i].add(devs[i].e_um, norms[i]);
    }
    ++n_points;
    tick();
    if (writer) writer->write(p, line, devs, norms);
  };

  const bool points_input = o.points || ends_with(o.input, ".csv") || ends_with(o.input, ".CSV");
  if (points_input) {
    PointReader reader(*in, o.input, machine.tool_length());
    model::EvalPoint p;
    std::size_t line = 0;
    while (reader.next(p, line)) evaluate(p, line);
  } else {
    const gcode::InterpreterConfig config = machine::interpreter_config(machine);
    path::FragmentOptions fo;
    fo.step = o.step;
    fo.rapid_rate = o.rapid_rate;
    path::Fragmenter fragmenter(fo);
    const path::PointSink sink = [&](const path::PathPoint& pp) {
      model::EvalPoint p;
      p.p = pp.p;
      p.tool_length = pp.tool_length;
      p.dir = pp.dir;
      p.time = pp.time;
      evaluate(p, pp.line);
    };
    gcode::run_program(*in, o.input, config,
                       [&](const gcode::Motion& m) { fragmenter.add(m, sink); });
  }

  progress.finish();
  // Summary.
  nlohmann::json summary;
  summary["machine"] = machine.name();
  summary["input"] = o.input;
  summary["points"] = n_points;
  summary["out_of_range_policy"] = machine::to_string(machine.out_of_range());
  summary["models"] = nlohmann::json::array();
  std::string text =
      fmt::format("{}: {} points, machine \"{}\"\n", o.input, n_points, machine.name());
  text +=
      fmt::format("  {:<7} {:>10} {:>10} {:>10} {:>10} {:>10} {:>12}\n", "model", "max|dx| µm",
                  "max|dy| µm", "max|dz| µm", "rms|d| µm", "max|d| µm",
                  machine.out_of_range() == machine::OutOfRangePolicy::extrapolate ? "extrapolated"
                                                                                   : "clamped");
  for (std::size_t i = 0; i < kinds.size(); ++i) {
    const ModelStats& s = stats[i];
    summary["models"].push_back({{"model", model::to_string(kinds[i])},
                                 {"points", s.points},
                                 {"max_abs_dx_um", s.max_abs.x()},
                                 {"max_abs_dy_um", s.max_abs.y()},
                                 {"max_abs_dz_um", s.max_abs.z()},
                                 {"rms_d_um", s.rms()},
                                 {"max_d_um", s.max_d},
                                 {"out_of_range_lookups", data[i].out_of_range_lookups}});
    text += fmt::format("  {:<7} {:>10.4f} {:>10.4f} {:>10.4f} {:>10.4f} {:>10.4f} {:>12}\n",
                        model::to_string(kinds[i]), s.max_abs.x(), s.max_abs.y(), s.max_abs.z(),
                        s.rms(), s.max_d, data[i].out_of_range_lookups);
  }
  if (writer) {
    writer->finish(summary);
    out->commit();
  }
  if (!o.summary_json.empty()) {
    io::AtomicOutputFile js(o.summary_json);
    std::string body = summary.dump(2) + "\n";
    js.write(body.data(), body.size());
    js.commit();
  }
  // The table goes to stdout unless the points do.
  const bool points_on_stdout = writer && (o.output == "-" || o.output.empty());
  std::fputs(text.c_str(), points_on_stdout ? stderr : stdout);
  return kOk;
}

const CommandRegistrar registrar(
    "predict",
    "Predict the deviation of the tool tip along an NC program or at the points of a CSV file", 30,
    [](CLI::App& sub, const GlobalOptions& g) -> CommandAction {
      auto o = std::make_shared<PredictOptions>();
      const GlobalOptions* gp = &g;
      sub.footer(
          "Example: abbe predict nc-samples/thesis-toolpath-1.ngc "
          "--machine machines/sample/machine.yaml --model all -o predicted.csv");
      sub.add_option("input", o->input,
                     "NC program, or a CSV of points (x,y,z[,vx,vy,vz,tool_length]); - for stdin")
          ->required();
      sub.add_option("--machine", o->machine, "Machine file (YAML, docs/formats.md)")->required();
      sub.add_option("--model", o->model, "Error model: htm, ae-arm, dual or all")
          ->check(CLI::IsMember({"htm", "ae-arm", "dual", "all"}))
          ->capture_default_str();
      sub.add_option("-o,--output", o->output, "Output file (written atomically), - for stdout")
          ->capture_default_str();
      sub.add_option("--format", o->format, "csv or json")
          ->check(CLI::IsMember({"csv", "json"}))
          ->capture_default_str();
      sub.add_option("--step", o->step, "Largest distance between points along the path, mm")
          ->check(CLI::PositiveNumber)
          ->capture_default_str();
      sub.add_option("--rapid-rate", o->rapid_rate, "Rate of rapid motions for the time, mm/min")
          ->check(CLI::PositiveNumber)
          ->capture_default_str();
      sub.add_flag("--points", o->points, "The input is a CSV of points (also for non-.csv names)");
      sub.add_flag("--summary-only", o->summary_only, "Write no points, only the summary");
      sub.add_option("--summary-json", o->summary_json, "Also write the summary as JSON to FILE");
      sub.add_option("--extend", o->extend,
                     "Add the effects of an overlay written by `abbe diagnose --overlay`");
      return [o, gp] { return run_predict(*o, *gp); };
    });

}  // namespace
}  // namespace abbe::cli
