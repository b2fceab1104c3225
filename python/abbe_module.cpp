// The Python module `abbe` (docs/python.md): the library's pipeline for
// NumPy users. A machine is loaded once; path() and predict() return NumPy
// arrays that own C++ buffers (no copy), diagnose() the report as a dict,
// compensate() the compensated program. Bad input raises abbe.InputError
// (a ValueError) with the file, line and column of the C++ message.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <cctype>
#include <cmath>
#include <fstream>
#include <memory>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "abbe/compensate/controller_tables.hpp"
#include "abbe/compensate/program_compensator.hpp"
#include "abbe/compensate/provenance.hpp"
#include "abbe/diagnose/diagnosis.hpp"
#include "abbe/gcode/dialect.hpp"
#include "abbe/io/atomic_file.hpp"
#include "abbe/io/input_error.hpp"
#include "abbe/io/measured_data.hpp"
#include "abbe/machine/machine.hpp"
#include "abbe/model/error_model.hpp"
#include "abbe/model/model_kind.hpp"
#include "abbe/pipeline/interpreter_setup.hpp"
#include "abbe/pipeline/model_set.hpp"
#include "abbe/pipeline/predict.hpp"
#include "abbe/pipeline/prediction_summary.hpp"
#include "abbe/pipeline/program_path.hpp"
#include "numpy_owned.hpp"

namespace py = pybind11;
using namespace abbe;
using abbe::python::owned_array;
using abbe::python::owned_matrix;

namespace {

// A program given as a file name (str or os.PathLike) or as text (code=...).
struct ProgramSource {
  std::string name;
  std::unique_ptr<std::istream> stream;
};

ProgramSource open_program(const py::object& program, const py::object& code) {
  ProgramSource s;
  if (!code.is_none()) {
    if (!program.is_none()) throw py::value_error("give either a program file or code=, not both");
    s.name = "<string>";
    s.stream = std::make_unique<std::istringstream>(code.cast<std::string>());
    return s;
  }
  if (program.is_none()) throw py::value_error("no program: give a file name or code=");
  s.name = py::str(py::module_::import("os").attr("fspath")(program)).cast<std::string>();
  auto file = std::make_unique<std::ifstream>(s.name, std::ios::binary);
  if (!*file) throw InputError({s.name, 0, 0, "", ""}, "cannot open the program");
  s.stream = std::move(file);
  return s;
}

gcode::DialectOptions parse_dialect(const std::string& name) {
  gcode::DialectOptions d;
  const auto dialect = gcode::dialect_from_name(name);
  if (!dialect)
    throw py::value_error("dialect must be \"linuxcnc\" or \"fanuc\", not \"" + name + "\"");
  d.dialect = *dialect;
  return d;
}

std::vector<model::ModelKind> parse_models(const std::string& text) {
  return model::parse_model_list(text);
}

pipeline::PathOptions path_options(double step, const std::string& dialect) {
  pipeline::PathOptions o;
  o.fragment.step = step;
  o.dialect = parse_dialect(dialect);
  return o;
}

py::object json_loads(const std::string& text) {
  return py::module_::import("json").attr("loads")(text);
}

// The points of a fragmented program, column by column.
struct PathColumns {
  std::vector<double> xyz, tool_length, feed, time;
  std::vector<std::int64_t> line;
  std::vector<std::int8_t> dir;
  std::vector<std::uint8_t> kind;
  void add(const path::PathPoint& p) {
    xyz.insert(xyz.end(), {p.p.x(), p.p.y(), p.p.z()});
    tool_length.push_back(p.tool_length);
    feed.push_back(p.feed);
    time.push_back(p.time);
    line.push_back(static_cast<std::int64_t>(p.line));
    dir.insert(dir.end(), p.dir.begin(), p.dir.end());
    kind.push_back(static_cast<std::uint8_t>(p.kind));
  }
  py::dict to_dict() {
    py::dict d;
    d["xyz"] = owned_matrix(std::move(xyz), 3);
    d["tool_length"] = owned_array(std::move(tool_length));
    d["line"] = owned_array(std::move(line));
    d["kind"] = owned_array(std::move(kind));
    d["feed"] = owned_array(std::move(feed));
    d["time"] = owned_array(std::move(time));
    d["dir"] = owned_matrix(std::move(dir), 3);
    return d;
  }
};

py::dict py_path(const py::object& program, const py::object& code,
                 const std::shared_ptr<machine::Machine>& machine, double step,
                 const std::string& dialect) {
  ProgramSource src = open_program(program, code);
  const gcode::InterpreterConfig config =
      machine ? pipeline::interpreter_config(*machine) : gcode::InterpreterConfig{};
  PathColumns cols;
  pipeline::PathRun run;
  {
    py::gil_scoped_release release;
    run = pipeline::run_path(*src.stream, src.name, config, path_options(step, dialect),
                             [&](const path::PathPoint& p) { cols.add(p); });
  }
  py::dict d = cols.to_dict();
  d["time_s"] = run.time_s;
  d["lines"] = run.program.lines;
  return d;
}

// Per model: deviations (n, 3) µm, |e| (n,) µm, and the ε² part for models
// that have one.
struct ModelColumns {
  std::vector<double> e_um, d_um, second_um;
};

py::dict predict_result(const std::vector<model::ModelKind>& kinds, std::vector<double>&& xyz,
                        std::vector<std::int64_t>&& lines, std::vector<ModelColumns>& per_model,
                        const pipeline::PredictionSummary& summary) {
  py::dict out;
  out["xyz"] = owned_matrix(std::move(xyz), 3);
  out["line"] = owned_array(std::move(lines));
  py::dict models;
  for (std::size_t k = 0; k < kinds.size(); ++k) {
    py::dict m;
    m["e_um"] = owned_matrix(std::move(per_model[k].e_um), 3);
    m["d_um"] = owned_array(std::move(per_model[k].d_um));
    if (model::descriptor(kinds[k]).second_order)
      m["second_order_um"] = owned_matrix(std::move(per_model[k].second_um), 3);
    models[model::to_string(kinds[k])] = m;
  }
  out["models"] = models;
  out["summary"] = json_loads(pipeline::summary_json(summary));
  return out;
}

void collect(const model::EvalPoint& point, std::size_t line, const pipeline::ModelSet& set,
             std::vector<double>& xyz, std::vector<std::int64_t>& lines,
             std::vector<ModelColumns>& per_model) {
  xyz.insert(xyz.end(), {point.p.x(), point.p.y(), point.p.z()});
  lines.push_back(static_cast<std::int64_t>(line));
  for (std::size_t k = 0; k < set.size(); ++k) {
    const model::Deviation& dev = set.deviations()[k];
    auto& c = per_model[k];
    c.e_um.insert(c.e_um.end(), {dev.e_um.x(), dev.e_um.y(), dev.e_um.z()});
    c.d_um.push_back(set.norms_um()[k]);
    c.second_um.insert(c.second_um.end(),
                       {dev.second_order_um.x(), dev.second_order_um.y(), dev.second_order_um.z()});
  }
}

// predict() on an (n, 3) array of nominal points (mm, machine coordinates),
// read in place (no copy for a C-ordered float64 array).
py::dict predict_points(const machine::Machine& machine,
                        const py::array_t<double, py::array::c_style | py::array::forcecast>& pts,
                        const std::vector<model::ModelKind>& kinds, double tool_length) {
  if (pts.ndim() != 2 || pts.shape(1) != 3)
    throw py::value_error("points must be an array of shape (n, 3) (x, y, z in mm)");
  const auto n = static_cast<std::size_t>(pts.shape(0));
  auto view = pts.unchecked<2>();
  std::vector<double> xyz;
  std::vector<std::int64_t> lines;
  std::vector<ModelColumns> per_model(kinds.size());
  xyz.reserve(3 * n);
  lines.reserve(n);
  pipeline::ModelSet set(machine, kinds);
  {
    py::gil_scoped_release release;
    model::EvalPoint point;
    point.tool_length = tool_length;
    for (std::size_t i = 0; i < n; ++i) {
      const auto r = static_cast<py::ssize_t>(i);
      point.p = {view(r, 0), view(r, 1), view(r, 2)};
      set.evaluate(point, "<points>", i + 1);
      collect(point, i + 1, set, xyz, lines, per_model);
    }
  }
  return predict_result(kinds, std::move(xyz), std::move(lines), per_model,
                        pipeline::summarize(set, machine, "<points>"));
}

py::dict py_predict(const std::shared_ptr<machine::Machine>& machine, const py::object& what,
                    const py::object& code, const std::string& model_names, double step,
                    const std::string& dialect, double tool_length) {
  const std::vector<model::ModelKind> kinds = parse_models(model_names);
  if (code.is_none() && py::isinstance<py::array>(what))
    return predict_points(
        *machine, what.cast<py::array_t<double, py::array::c_style | py::array::forcecast>>(),
        kinds, tool_length);
  if (code.is_none() && !what.is_none() && !py::isinstance<py::str>(what) &&
      !py::hasattr(what, "__fspath__"))
    return predict_points(
        *machine, py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(what),
        kinds, tool_length);
  ProgramSource src = open_program(what, code);
  pipeline::PredictOptions o;
  o.models = kinds;
  o.path = path_options(step, dialect);
  o.input = pipeline::predict_input_of(src.name, false);
  std::vector<double> xyz;
  std::vector<std::int64_t> lines;
  std::vector<ModelColumns> per_model(kinds.size());
  pipeline::PredictionSummary summary;
  {
    py::gil_scoped_release release;
    summary = pipeline::predict(
        *src.stream, src.name, *machine, o,
        [&](const model::EvalPoint& p, std::size_t line, const pipeline::ModelSet& set) {
          collect(p, line, set, xyz, lines, per_model);
        });
  }
  return predict_result(kinds, std::move(xyz), std::move(lines), per_model, summary);
}

py::object py_diagnose(const std::shared_ptr<machine::Machine>& machine, const py::object& measured,
                       const std::string& model_name, int folds, std::uint64_t seed,
                       const py::object& extend, bool infer_directions,
                       const py::object& table_uncertainty) {
  auto path_of = [](const py::object& p) {
    return py::str(py::module_::import("os").attr("fspath")(p)).cast<std::string>();
  };
  const std::string file = path_of(measured);
  std::optional<diagnose::Overlay> overlay;
  if (!extend.is_none()) overlay = diagnose::Overlay::load(path_of(extend));
  diagnose::DiagnoseOptions opt;
  if (overlay) opt.extend = &*overlay;
  const auto kind = model::parse_model_kind(model_name);
  if (!kind)
    throw py::value_error("unknown model \"" + model_name + "\" (" +
                          model::model_names_text(false) + ")");
  opt.model = *kind;
  opt.selection.folds = folds;
  opt.selection.seed = seed;
  opt.infer_directions = infer_directions;
  if (!table_uncertainty.is_none()) opt.tables.draws = table_uncertainty.cast<std::size_t>();
  opt.tables.seed = seed;
  std::string report;
  {
    py::gil_scoped_release release;
    const io::MeasuredData data = io::load_measured_data(file);
    report = diagnose::report_json(diagnose::diagnose(*machine, data, opt));
  }
  return json_loads(report);
}

py::tuple py_compensate(const std::shared_ptr<machine::Machine>& machine, const py::object& program,
                        const py::object& code, const std::string& model_name, double tol_um,
                        double step, const std::string& dialect, double min_segment,
                        bool spread_takeups) {
  ProgramSource src = open_program(program, code);
  const auto kind = model::parse_model_kind(model_name);
  if (!kind)
    throw py::value_error("unknown model \"" + model_name + "\" (" +
                          model::model_names_text(false) + ")");
  gcode::InterpreterConfig config = pipeline::interpreter_config(*machine);
  config.dialect = parse_dialect(dialect);
  compensate::CompensateOptions o;
  o.tol_um = tol_um;
  o.step = step;
  o.min_segment = min_segment;
  o.spread_takeups = spread_takeups;
  // As `abbe compensate`: the machine's travel is enforced and the output
  // starts with its provenance block.
  o.travel = machine->spec().travel;
  o.provenance =
      compensate::make_provenance(ABBE_VERSION, *machine, config, model_name, "", 0.0, o);
  std::string text;
  compensate::CompensateSummary s;
  {
    py::gil_scoped_release release;
    const model::ErrorModel error_model(*machine, *kind);
    s = compensate::compensate_program(*src.stream, src.name, config, error_model, o,
                                       [&](const char* d, std::size_t n) { text.append(d, n); });
  }
  py::dict summary;
  summary["lines"] = s.lines;
  summary["blocks_changed"] = s.blocks_changed;
  summary["pieces_inserted"] = s.pieces_inserted;
  summary["takeup_moves"] = s.takeup_moves;
  summary["takeups_spread"] = s.takeups_spread;
  summary["max_takeup_um"] = s.max_takeup_um;
  summary["short_pieces_kept"] = s.short_pieces_kept;
  summary["short_takeup_moves"] = s.short_takeup_moves;
  summary["shortest_inserted_mm"] = s.shortest_inserted_mm;
  summary["points"] = s.points;
  summary["max_correction_um"] = s.max_correction_um;
  summary["out_of_range_points"] = s.out_of_range_points;
  summary["unconverged_points"] = s.unconverged_points;
  summary["warnings"] = s.warnings;
  return py::make_tuple(text, summary);
}

// export_linuxcnc(): the per-joint tables as arrays and texts (as `abbe
// export linuxcnc`); with `directory` the files are written too.
py::dict py_export_linuxcnc(const std::shared_ptr<machine::Machine>& machine,
                            const py::object& directory, const std::string& model_name,
                            const py::object& at, const py::object& tool_length, double step,
                            const std::string& units) {
  compensate::JointTableOptions o;
  const std::vector<model::ModelKind> kinds = parse_models(model_name);
  if (kinds.size() != 1) throw py::value_error("a LinuxCNC table holds one model");
  o.model = kinds[0];
  o.tool_length = tool_length.is_none() ? machine->tool_length() : tool_length.cast<double>();
  if (at.is_none()) {
    o.at_tip = compensate::travel_centre_tip(*machine, o.tool_length);
  } else {
    const auto v = at.cast<std::vector<double>>();
    if (v.size() != 3) throw py::value_error("at must be (x, y, z) in mm");
    o.at_tip = Eigen::Vector3d(v[0], v[1], v[2]);
  }
  o.step = step;
  if (units != "mm" && units != "inch") throw py::value_error("units must be \"mm\" or \"inch\"");
  o.inch = units == "inch";
  const auto tables = compensate::joint_tables(*machine, o);
  py::dict d;
  for (const auto& t : tables) {
    py::dict a;
    a["nominal_mm"] = owned_array(std::vector<double>(t.nominal_mm));
    a["forward_um"] = owned_array(std::vector<double>(t.forward_um));
    a["reverse_um"] = owned_array(std::vector<double>(t.reverse_um));
    a["text"] = compensate::linuxcnc_comp_text(t, o.inch);
    d[py::str(std::string(1, static_cast<char>(std::tolower(machine::axis_letter(t.axis)))))] = a;
  }
  d["ini"] = compensate::linuxcnc_ini_text(*machine, o, tables);
  if (!directory.is_none())
    compensate::export_linuxcnc(
        *machine, o,
        py::str(py::module_::import("os").attr("fspath")(directory)).cast<std::string>());
  return d;
}

// volumetric_grid(): the grid's nodes and per-model deviations (as `abbe
// export grid`); with `output` the CSV is written too.
py::dict py_volumetric_grid(const std::shared_ptr<machine::Machine>& machine,
                            const std::string& model_names, const py::object& step,
                            const py::object& count, const py::object& tool_length,
                            const py::object& output) {
  compensate::GridOptions o;
  o.models = parse_models(model_names);
  o.tool_length = tool_length.is_none() ? machine->tool_length() : tool_length.cast<double>();
  auto three = [](const py::object& v, const char* name) {
    if (py::isinstance<py::float_>(v) || py::isinstance<py::int_>(v))
      return std::vector<double>(3, v.cast<double>());
    auto r = v.cast<std::vector<double>>();
    if (r.size() != 3) throw py::value_error(std::string(name) + " must be one value or three");
    return r;
  };
  if (!step.is_none() && !count.is_none()) throw py::value_error("give step or count, not both");
  if (!step.is_none()) {
    const auto s = three(step, "step");
    o.step = Eigen::Vector3d(s[0], s[1], s[2]);
  }
  if (!count.is_none()) {
    const auto c = three(count, "count");
    for (std::size_t a = 0; a < 3; ++a) {
      if (!(c[a] >= 2.0) || c[a] != std::floor(c[a])) throw py::value_error("count: integers >= 2");
      o.count[a] = static_cast<std::size_t>(c[a]);
    }
  }
  compensate::VolumetricGrid grid;
  {
    py::gil_scoped_release release;
    grid = compensate::volumetric_grid(*machine, o);
  }
  py::dict d;
  d["x"] = owned_array(std::vector<double>(grid.nodes[0]));
  d["y"] = owned_array(std::vector<double>(grid.nodes[1]));
  d["z"] = owned_array(std::vector<double>(grid.nodes[2]));
  d["tool_length"] = grid.tool_length;
  py::dict models;
  for (std::size_t m = 0; m < grid.models.size(); ++m) {
    std::vector<double> e;
    e.reserve(3 * grid.size());
    for (const auto& v : grid.deviation_um[m]) e.insert(e.end(), {v.x(), v.y(), v.z()});
    models[py::str(model::to_string(grid.models[m]))] = owned_matrix(std::move(e), 3);
  }
  d["models"] = models;
  if (!output.is_none()) {
    const std::string text = compensate::grid_csv_text(grid);
    io::AtomicOutputFile f(
        py::str(py::module_::import("os").attr("fspath")(output)).cast<std::string>());
    f.write(text.data(), text.size());
    f.commit();
  }
  return d;
}

}  // namespace

PYBIND11_MODULE(abbe, m) {
  m.doc() = "abbe: predict how far a 3-axis machine tool deviates along an NC program, and why";
  m.attr("__version__") = ABBE_VERSION;
  py::register_exception<InputError>(m, "InputError", PyExc_ValueError);

  py::class_<machine::Machine, std::shared_ptr<machine::Machine>>(m, "Machine",
                                                                  "A machine file (YAML)")
      .def(py::init([](const py::object& file) {
             return std::make_shared<machine::Machine>(machine::Machine::load(
                 py::str(py::module_::import("os").attr("fspath")(file)).cast<std::string>()));
           }),
           py::arg("file"), "Loads a machine file (docs/formats.md)")
      .def_property_readonly("name", &machine::Machine::name)
      .def("__repr__",
           [](const machine::Machine& mm) { return "<abbe.Machine \"" + mm.name() + "\">"; });

  m.def(
      "load_machine",
      [](const py::object& file) {
        return std::make_shared<machine::Machine>(machine::Machine::load(
            py::str(py::module_::import("os").attr("fspath")(file)).cast<std::string>()));
      },
      py::arg("file"), "Loads a machine file (same as abbe.Machine(file))");

  m.def("path", &py_path, py::arg("program") = py::none(), py::kw_only(),
        py::arg("code") = py::none(), py::arg("machine") = nullptr, py::arg("step") = 5.0,
        py::arg("dialect") = "linuxcnc",
        "The fragmented toolpath of a program (file name, or code=TEXT): a dict of NumPy "
        "arrays xyz (n, 3) mm, tool_length, line, kind (0 rapid, 1 linear, 2 arc), feed "
        "(mm/min), time (s), dir (n, 3); machine=None runs without tool table and offsets.");
  m.def("predict", &py_predict, py::arg("machine"), py::arg("input") = py::none(), py::kw_only(),
        py::arg("code") = py::none(), py::arg("model") = "ae-arm", py::arg("step") = 5.0,
        py::arg("dialect") = "linuxcnc", py::arg("tool_length") = 0.0,
        "Predicted deviations along a program (file name or code=TEXT), a CSV of points "
        "(.csv), or an (n, 3) array of nominal points (mm): a dict with xyz, line and "
        "models[name] = {e_um (n, 3), d_um (n,)[, second_order_um]}, and the summary. "
        "model: a name, a comma-separated list or \"all\".");
  m.def("diagnose", &py_diagnose, py::arg("machine"), py::arg("measured"), py::kw_only(),
        py::arg("model") = "ae-arm", py::arg("folds") = 5, py::arg("seed") = 1,
        py::arg("extend") = py::none(), py::arg("infer_directions") = false,
        py::arg("table_uncertainty") = py::none(),
        "Diagnosis of measured data (CSV) against the machine's model: the JSON report of "
        "`abbe diagnose` as a dict. extend: an earlier overlay (YAML path) added to the model "
        "first; the report's extend_check says what it does on these data. "
        "infer_directions: approach directions from the order of the points where the data "
        "have none (as --infer-directions). table_uncertainty: N Monte Carlo draws of the "
        "campaign's uncertainty in every effect's u (as --table-uncertainty; None: 50 where the "
        "machine file gives an uncertainty, 0: the data's u alone; seed draws them too; each "
        "effect's stderr_data and stderr_tables give the parts).");
  m.def("compensate", &py_compensate, py::arg("machine"), py::arg("program") = py::none(),
        py::kw_only(), py::arg("code") = py::none(), py::arg("model") = "ae-arm",
        py::arg("tol_um") = 1.0, py::arg("step") = 5.0, py::arg("dialect") = "linuxcnc",
        py::arg("min_segment") = 0.01, py::arg("spread_takeups") = false,
        "The compensated program as text and a summary dict (as `abbe compensate`).");
  m.def("export_linuxcnc", &py_export_linuxcnc, py::arg("machine"),
        py::arg("directory") = py::none(), py::kw_only(), py::arg("model") = "ae-arm",
        py::arg("at") = py::none(), py::arg("tool_length") = py::none(), py::arg("step") = 0.0,
        py::arg("units") = "mm",
        "LinuxCNC per-joint compensation tables (as `abbe export linuxcnc`, docs/export.md): "
        "a dict x, y, z = {nominal_mm, forward_um, reverse_um (predicted error along the "
        "axis), text (the COMP_FILE_TYPE 1 file)} and ini; with directory the files are "
        "written there.");
  m.def("volumetric_grid", &py_volumetric_grid, py::arg("machine"), py::kw_only(),
        py::arg("model") = "ae-arm", py::arg("step") = py::none(), py::arg("count") = py::none(),
        py::arg("tool_length") = py::none(), py::arg("output") = py::none(),
        "The volumetric grid (as `abbe export grid`): nodes x, y, z (mm, tool tip) and "
        "models[name] = deviations (nx·ny·nz, 3) µm, x fastest; with output the CSV is "
        "written there.");
}
