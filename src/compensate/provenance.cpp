#include "abbe/compensate/provenance.hpp"

#include <fmt/format.h>

#include <sstream>

#include "abbe/compensate/program_compensator.hpp"
#include "abbe/io/input_error.hpp"
#include "abbe/io/sha256.hpp"
#include "abbe/io/utc_timestamp.hpp"

namespace abbe::compensate {
namespace {

// A path in a comment: a parenthesis would end the comment early.
std::string comment_safe(std::string s) {
  for (char& c : s)
    if (c == '(' || c == ')' || c == '\r' || c == '\n') c = '_';
  return s;
}

std::string trim(std::string_view s) {
  while (!s.empty() && (s.back() == '\r' || s.back() == ' ' || s.back() == '\t'))
    s.remove_suffix(1);
  while (!s.empty() && (s.front() == ' ' || s.front() == '\t')) s.remove_prefix(1);
  return std::string(s);
}

std::string mm(double v) { return fmt::format("{:.4f}", v); }

}  // namespace

FileFingerprint file_fingerprint(const std::string& role, const std::string& path) {
  return {role, io::sha256_file(path), comment_safe(path)};
}

std::vector<FileFingerprint> machine_fingerprints(const machine::Machine& machine) {
  std::vector<FileFingerprint> out;
  const auto& spec = machine.spec();
  if (!spec.file.empty() && spec.file != "<memory>")
    out.push_back(file_fingerprint("machine-file", spec.file));
  if (!spec.table_file.empty()) out.push_back(file_fingerprint("table-file", spec.table_file));
  return out;
}

std::vector<std::string> setup_lines(const gcode::InterpreterConfig& config) {
  std::vector<std::string> out;
  static const char* kCodes[6] = {"G54", "G55", "G56", "G57", "G58", "G59"};
  std::string offsets = "work offsets in machine coordinates, mm:";
  for (std::size_t i = 0; i < 6; ++i) {
    const auto& v = config.work_offsets[i];
    offsets += fmt::format(" {} X{} Y{} Z{}", kCodes[i], mm(v.x()), mm(v.y()), mm(v.z()));
    if (i == 0 && config.work_offsets[1].isZero() && config.work_offsets[2].isZero() &&
        config.work_offsets[3].isZero() && config.work_offsets[4].isZero() &&
        config.work_offsets[5].isZero()) {
      offsets += ", G55-G59 zero";
      break;
    }
  }
  out.push_back(offsets);
  std::string tools =
      fmt::format("tool lengths, mm: without G43 {}", mm(config.default_tool_length));
  for (const auto& [h, l] : config.tool_lengths) tools += fmt::format(", H{} {}", h, mm(l));
  out.push_back(tools);
  const auto& s = config.initial_position;
  out.push_back(fmt::format("start: tool tip at X{} Y{} Z{} mm in machine coordinates", mm(s.x()),
                            mm(s.y()), mm(s.z())));
  return out;
}

std::string format_provenance(const Provenance& p, std::string_view eol) {
  std::string out;
  auto line = [&](const std::string& text) {
    out += text;
    out += eol;
  };
  line(fmt::format("{} by abbe {}: do not compensate this program again)", kProvenanceMarker,
                   comment_safe(p.version)));
  for (const auto& f : p.files)
    line(fmt::format("(abbe {} sha256={} {})", f.role, f.sha256, comment_safe(f.path)));
  line(fmt::format("(abbe model {})", comment_safe(p.model)));
  if (!p.overlay_time_s.empty())
    line(fmt::format("(abbe overlay-time {} s)", comment_safe(p.overlay_time_s)));
  line(fmt::format("(abbe tol {} um step {} mm min-segment {} mm takeups {})", p.tol_um, p.step_mm,
                   p.min_segment_mm, p.spread_takeups ? "spread" : "micro"));
  for (const auto& s : p.setup) line(fmt::format("(abbe setup {})", comment_safe(s)));
  line(
      "(abbe setup valid only for these offsets, tool lengths and start point: check them at "
      "the machine)");
  line(fmt::format("(abbe date {})", comment_safe(p.date)));
  return out;
}

Provenance make_provenance(const std::string& version, const machine::Machine& machine,
                           const gcode::InterpreterConfig& config, const std::string& model,
                           const std::string& overlay, double overlay_time_s,
                           const CompensateOptions& options) {
  Provenance p;
  p.version = version;
  p.files = machine_fingerprints(machine);
  p.model = model;
  if (!overlay.empty()) {
    p.files.push_back(file_fingerprint("overlay-file", overlay));
    p.model += " + overlay";
    p.overlay_time_s = fmt::format("{}", overlay_time_s);
  }
  p.tol_um = options.tol_um;
  p.step_mm = options.step;
  p.min_segment_mm = options.min_segment;
  p.spread_takeups = options.spread_takeups;
  p.setup = setup_lines(config);
  p.date = io::utc_timestamp();
  return p;
}

bool carries_provenance(std::string_view line) {
  return line.find(kProvenanceMarker) != std::string_view::npos;
}

std::optional<Provenance> read_provenance(std::istream& in) {
  std::string raw;
  std::optional<Provenance> p;
  std::size_t n = 0;
  while (std::getline(in, raw)) {
    ++n;
    const std::string l = trim(raw);
    if (!p) {
      if (carries_provenance(l) && l.rfind(kProvenanceMarker, 0) == 0) {
        p.emplace();
        p->line = n;
        const auto by = l.find(" by abbe ");
        if (by != std::string::npos) {
          const auto colon = l.find(':', by);
          p->version =
              l.substr(by + 9, colon == std::string::npos ? std::string::npos : colon - by - 9);
        }
        continue;
      }
      // Only a "%" line and an O number line may come before it.
      if (n <= 2 && (l == "%" || (!l.empty() && (l[0] == 'O' || l[0] == 'o')))) continue;
      return std::nullopt;
    }
    if (l.rfind("(abbe ", 0) != 0 || l.back() != ')') break;
    std::istringstream words(l.substr(6, l.size() - 7));
    std::string key;
    words >> key;
    if (key == "machine-file" || key == "table-file" || key == "overlay-file") {
      FileFingerprint f;
      f.role = key;
      std::string sha;
      words >> sha;
      if (sha.rfind("sha256=", 0) == 0) f.sha256 = sha.substr(7);
      std::getline(words >> std::ws, f.path);
      p->files.push_back(f);
    } else if (key == "model") {
      std::getline(words >> std::ws, p->model);
    } else if (key == "date") {
      words >> p->date;
    } else if (key == "setup") {
      std::string s;
      std::getline(words >> std::ws, s);
      p->setup.push_back(s);
    } else if (key == "tol") {
      std::string unit, k2, k3;
      words >> p->tol_um >> unit >> k2 >> p->step_mm >> unit >> k3;
      if (k3 == "min-segment") words >> p->min_segment_mm;
    }
  }
  return p;
}

void check_machine_files(const Provenance& p, const std::string& file,
                         const std::vector<FileFingerprint>& current) {
  for (const auto& f : p.files) {
    for (const auto& c : current) {
      if (c.role != f.role || c.sha256 == f.sha256) continue;
      throw InputError(
          {file, p.line, 0, "", ""},
          fmt::format("the program was compensated for {} {} (sha256 {}), but {} has other "
                      "content (sha256 {}): verify with the machine files it was compensated for",
                      f.role, f.path, f.sha256.substr(0, 16), c.path, c.sha256.substr(0, 16)));
    }
  }
}

void check_setup(const Provenance& p, const std::string& file,
                 const std::vector<std::string>& current) {
  for (const auto& c : current) {
    const std::string line = comment_safe(c);
    const auto colon = line.find(':');
    for (const auto& s : p.setup) {
      if (s.compare(0, colon, line, 0, colon) != 0 || s == line) continue;
      throw InputError({file, p.line, 0, "", ""},
                       fmt::format("the program was compensated for the setup \"{}\", verify "
                                   "was given \"{}\" (the same --tool, --tool-length and "
                                   "--work-offset as for compensate)",
                                   s, line));
    }
  }
}

}  // namespace abbe::compensate
