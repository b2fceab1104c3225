"""Tests of the Python module abbe (python/abbe_module.cpp, docs/python.md).

Run by ctest (tests/cli/python.cmake) with PYTHONPATH at the built module and
ABBE_SOURCE_DIR at the source tree; the CLI binary (ABBE_EXE) gives the
reference numbers the module must reproduce.
"""
import csv
import io
import os
import pathlib
import subprocess

import numpy as np
import pytest

import abbe

ROOT = pathlib.Path(os.environ.get("ABBE_SOURCE_DIR", pathlib.Path(__file__).parents[2]))
MACHINE = ROOT / "machines/sample/machine.yaml"
PROGRAM = ROOT / "nc-samples/thesis-toolpath-1.ngc"
MEASURED = ROOT / "machines/sample/measured-grid.csv"


@pytest.fixture(scope="module")
def machine():
    return abbe.Machine(MACHINE)


def cli_text(*args):
    exe = os.environ.get("ABBE_EXE")
    assert exe, "ABBE_EXE (the abbe binary) is not set"
    env = dict(os.environ)
    env.pop("LD_PRELOAD", None)
    out = subprocess.run([exe, *map(str, args)], check=True, capture_output=True, env=env)
    return out.stdout.decode()


def cli(*args):
    return list(csv.DictReader(io.StringIO(cli_text(*args))))


def test_machine_loads(machine):
    assert machine.name
    assert "abbe.Machine" in repr(machine)
    assert abbe.load_machine(str(MACHINE)).name == machine.name


def test_path_arrays_match_cli(machine):
    p = abbe.path(PROGRAM, machine=machine)
    n = len(p["line"])
    assert n > 10
    assert p["xyz"].shape == (n, 3)
    assert p["dir"].shape == (n, 3)
    for key in ("tool_length", "kind", "feed", "time"):
        assert p[key].shape == (n,)
    assert np.all(np.diff(p["time"]) >= 0)
    rows = cli("path", PROGRAM, "--machine", MACHINE)
    assert len(rows) == n
    ref = np.array([[float(r["x"]), float(r["y"]), float(r["z"])] for r in rows])
    np.testing.assert_allclose(p["xyz"], ref, atol=1e-9)
    assert [int(r["line"]) for r in rows] == p["line"].tolist()


def test_path_from_code_without_machine():
    p = abbe.path(code="G21 G90\nG0 X0 Y0 Z0\nG1 X10 F100\n", step=2.5)
    x = p["xyz"][:, 0]
    np.testing.assert_allclose(x, [0, 2.5, 5, 7.5, 10])
    assert p["line"].tolist() == [2, 3, 3, 3, 3]
    assert p["kind"].tolist() == [0, 1, 1, 1, 1]


def test_arrays_are_not_copies(machine):
    p = abbe.path(PROGRAM, machine=machine)
    # The arrays view buffers owned by C++ (kept alive by a capsule).
    assert not p["xyz"].flags.owndata
    assert p["xyz"].flags.c_contiguous


def test_predict_program_matches_cli(machine):
    r = abbe.predict(machine, PROGRAM, model="all")
    assert set(r["models"]) == {"htm", "ae-arm", "dual"}
    rows = cli("predict", PROGRAM, "--machine", MACHINE, "--model", "ae-arm", "-o", "-")
    d = r["models"]["ae-arm"]["d_um"]
    assert len(rows) == len(d)
    # The CSV has 6 decimals (0.5e-6 µm rounding).
    np.testing.assert_allclose(d, [float(row["d"]) for row in rows], rtol=0, atol=5.1e-7)
    e = r["models"]["ae-arm"]["e_um"]
    np.testing.assert_allclose(np.linalg.norm(e, axis=1), d, rtol=1e-12)
    assert "second_order_um" in r["models"]["dual"]
    s = r["summary"]
    assert s["points"] == len(d)
    assert [m["model"] for m in s["models"]] == ["htm", "ae-arm", "dual"]


def test_predict_points_array_and_list(machine):
    prog = abbe.predict(machine, PROGRAM, model="htm")
    pts = abbe.predict(machine, prog["xyz"], model="htm")
    # The same points through a list (converted) give the same numbers as
    # through an array (read in place).
    as_list = abbe.predict(machine, prog["xyz"].tolist(), model="htm")
    np.testing.assert_array_equal(pts["models"]["htm"]["e_um"], as_list["models"]["htm"]["e_um"])
    np.testing.assert_array_equal(pts["xyz"], prog["xyz"])
    assert pts["line"].tolist() == list(range(1, len(pts["line"]) + 1))


def test_predict_zero_at_origin_is_finite_and_shapes(machine):
    r = abbe.predict(machine, np.zeros((4, 3)), model="ae-arm")
    e = r["models"]["ae-arm"]["e_um"]
    assert e.shape == (4, 3)
    assert np.all(np.isfinite(e))
    # The same point gives the same deviation.
    assert np.all(e == e[0])


def test_bad_points_shape(machine):
    with pytest.raises(ValueError, match=r"shape \(n, 3\)"):
        abbe.predict(machine, np.zeros((4, 2)))


def test_bad_program_names_line_and_column():
    with pytest.raises(abbe.InputError, match=r"<string>:2:1: error: cutter radius compensation"):
        abbe.path(code="G21\nG41 G1 X1 F100\n")


def test_missing_machine_file():
    with pytest.raises(abbe.InputError, match="no-such-machine.yaml"):
        abbe.Machine("no-such-machine.yaml")


def test_unknown_model(machine):
    with pytest.raises(ValueError, match="unknown model"):
        abbe.predict(machine, PROGRAM, model="nope")


def test_diagnose_returns_report_dict(machine):
    d = abbe.diagnose(machine, MEASURED, folds=3)
    assert d["model"] == "ae-arm"
    assert d["n_points"] > 0
    assert isinstance(d["effects"], list)
    assert {"htm", "ae-arm", "dual"} <= {m["model"] for m in d["models"]}


def test_diagnose_says_which_points_lie_outside_the_travel(machine, tmp_path):
    # The plug plates' drilling coordinates (±330 mm) on the sample machine,
    # whose X and Y travels end at 0: the points the machine cannot reach
    # are counted, and the warning asks for machine coordinates.
    plates = ROOT / "tests/data/plugplate"
    cli_text("import", "plugplate", plates / "D8131_1", "-o", tmp_path / "8131.csv")
    d = abbe.diagnose(machine, tmp_path / "8131.csv", folds=3)
    assert 0 < d["outside_travel_points"] <= d["n_points"]
    assert "points outside the travel" in d["travel_warning"]
    assert "machine coordinates" in d["travel_warning"]
    inside = abbe.diagnose(abbe.Machine(plates / "machine.yaml"), tmp_path / "8131.csv", folds=3)
    assert inside["outside_travel_points"] == 0
    assert "travel_warning" not in inside


def test_diagnose_adds_the_tables_uncertainty(machine):
    # The walk-through's grid against the sample machine with its campaign's
    # uncertainty: every named value's u holds the data's part and the
    # tables' part, √(data² + tables²); without an uncertainty in the
    # machine file the call is refused, naming the file and the key.
    sample = ROOT / "machines/sample"
    grid = sample / "measured-grid.csv"
    d = abbe.diagnose(abbe.Machine(sample / "machine-uncertainty.yaml"), grid,
                      table_uncertainty=20)
    assert d["table_uncertainty"]["draws"] == 20
    assert d["table_uncertainty_available"] is True
    drift = d["effects"][0]
    assert drift["kind"] == "thermal_drift"
    data, tables, u = drift["stderr_data"], drift["stderr_tables"], drift["stderr"]
    assert tables["um"] > 0
    assert u["um"] == pytest.approx((data["um"] ** 2 + tables["um"] ** 2) ** 0.5)
    assert u["tau_s"] == pytest.approx((data["tau_s"] ** 2 + tables["tau_s"] ** 2) ** 0.5)
    plain = abbe.diagnose(machine, grid)
    assert "table_uncertainty" not in plain
    assert plain["table_uncertainty_available"] is False
    # By default 50 draws where the machine gives an uncertainty; 0: none.
    mu = abbe.Machine(sample / "machine-uncertainty.yaml")
    assert abbe.diagnose(mu, grid)["table_uncertainty"]["draws"] == 50
    off = abbe.diagnose(mu, grid, table_uncertainty=0)
    assert "table_uncertainty" not in off and "stderr_tables" not in off["effects"][0]
    with pytest.raises(Exception, match=r"machine\.yaml.*uncertainty.*nothing to propagate"):
        abbe.diagnose(machine, grid, table_uncertainty=20)


def test_diagnose_with_an_earlier_overlay(tmp_path):
    # Plate 8131's extended model on plate 8132 (same batch): the report says
    # what it does there after 8132's own datum, as `abbe diagnose --extend`.
    plates = ROOT / "tests/data/plugplate"
    plate_machine = abbe.Machine(plates / "machine.yaml")
    for plate in ("D8131_1", "D8132_1"):
        cli_text("import", "plugplate", plates / plate, "-o", tmp_path / f"{plate}.csv")
    overlay = tmp_path / "8131.yaml"
    cli_text("diagnose", "--machine", plates / "machine.yaml", "--measured",
             tmp_path / "D8131_1.csv", "--overlay", overlay)
    d = abbe.diagnose(plate_machine, tmp_path / "D8132_1.csv", extend=overlay)
    check = d["extend_check"]
    assert check["terms"] == 1
    assert check["rms_with_um"] < check["rms_without_um"]
    assert check["change_percent"] > 10
    assert "extend_check" not in abbe.diagnose(plate_machine, tmp_path / "D8132_1.csv")
    # What a plate cannot test: dz, time, approach directions, a second z.
    blind = [b["what"] for b in d["blind_spots"]]
    assert any(w.startswith("every effect in Z") for w in blind)
    assert any(w.startswith("a drift in time") for w in blind)


def test_diagnose_reports_the_linear_part_of_a_smooth_function(tmp_path):
    # Plate 2130A: its plate scale (about -25 ppm in X and Y) lies inside two
    # `unexplained` functions; the dict gives their linear parts with their
    # uncertainties, and the isotropic scale they agree on.
    plates = ROOT / "tests/data/plugplate"
    cli_text("import", "plugplate", plates / "D2130A1", "-o", tmp_path / "2130A.csv")
    d = abbe.diagnose(abbe.Machine(plates / "machine.yaml"), tmp_path / "2130A.csv")
    scales = {}
    for e in d["effects"]:
        assert e["kind"] == "unexplained"
        for part in e["linear_part"]["terms"]:
            if part["kind"] == "scale":
                scales[part["axis"]] = (part["params"]["ppm"], part["stderr"]["ppm"])
        assert 0.0 < e["linear_part"]["share"] <= 1.0
    assert set(scales) == {"X", "Y"}
    for value, u in scales.values():
        assert -30.0 < value < -20.0 and 0.3 < u < 2.0
    iso = d["isotropic_scale"]
    assert iso["axes"] == ["X", "Y"] and iso["from_linear_part"] == [True, True]


def test_diagnose_infers_approach_directions(machine, tmp_path):
    # A reversal of Y hidden in a grid; the file without vx vy vz: the
    # reversal cannot be tested (a blind spot) unless the directions are
    # taken from the order of the points, and then it is named.
    measured = tmp_path / "rev.csv"
    cli_text("simulate", "measure", "--truth", ROOT / "machines/sample/truth.yaml", "--grid",
             "100", "--inject", "reversal:Y:8um", "--seed", "3", "-o", measured)
    rows = list(csv.DictReader(measured.open()))
    fields = [f for f in rows[0] if f not in ("vx", "vy", "vz")]
    stripped = tmp_path / "rev-no-v.csv"
    with stripped.open("w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=fields, extrasaction="ignore")
        w.writeheader()
        w.writerows(rows)
    plain = abbe.diagnose(machine, stripped, folds=3)
    assert plain["directions_inferred"] == []
    assert any(b["what"].startswith("a reversal of Y") for b in plain["blind_spots"])
    assert not any(e["kind"] == "reversal" for e in plain["effects"])
    inferred = abbe.diagnose(machine, stripped, folds=3, infer_directions=True)
    assert inferred["directions_inferred"] == ["X", "Y", "Z"]
    blind = [b["what"] for b in inferred["blind_spots"]]
    assert not any(w.startswith(("a reversal of X", "a reversal of Y")) for w in blind)
    # The grid walks its Z levels down only: Z is approached from one side.
    assert any(w.startswith("a reversal of Z") for w in blind)
    named = [e for e in inferred["effects"] if e["kind"] == "reversal" and e["axis"] == "Y"]
    assert named and named[0].get("status", "named") == "named"


def test_compensate_returns_program(machine, monkeypatch):
    # One date for the provenance block of both runs.
    monkeypatch.setenv("SOURCE_DATE_EPOCH", "0")
    text, summary = abbe.compensate(machine, PROGRAM, tol_um=1.0)
    assert text != PROGRAM.read_text()
    assert summary["blocks_changed"] > 0
    assert summary["unconverged_points"] == 0
    assert summary["max_correction_um"] > 0
    # Byte for byte what the command writes.
    assert text == cli_text("compensate", PROGRAM, "--machine", MACHINE, "--tol", "1", "-o", "-")
    # From text too.
    text2, _ = abbe.compensate(machine, code=PROGRAM.read_text())
    assert text2 == text
