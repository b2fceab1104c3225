"""abbe.export_linuxcnc and abbe.volumetric_grid (docs/export.md): the same
tables as `abbe export linuxcnc` / `abbe export grid`, thin over the library."""
import os
import pathlib
import subprocess

import numpy as np
import pytest

import abbe

ROOT = pathlib.Path(os.environ.get("ABBE_SOURCE_DIR", pathlib.Path(__file__).parents[2]))
MACHINE = ROOT / "machines/sample/machine.yaml"
ZERO = ROOT / "tests/data/compensate/zero.yaml"


def test_linuxcnc_matches_the_cli(tmp_path):
    m = abbe.Machine(MACHINE)
    t = abbe.export_linuxcnc(m, tmp_path / "py", at=(-495, -250, -410), tool_length=130)
    assert "COMP_FILE_TYPE = 1" in t["ini"]
    x = t["x"]
    assert x["nominal_mm"][0] == -990 and x["nominal_mm"][-1] == 0
    assert np.all(np.diff(x["nominal_mm"]) > 0) and len(x["nominal_mm"]) <= 256
    # The file holds −error in mm.
    first = x["text"].splitlines()[0].split()
    assert float(first[1]) == pytest.approx(-x["forward_um"][0] / 1000, abs=1e-6)
    assert float(first[2]) == pytest.approx(-x["reverse_um"][0] / 1000, abs=1e-6)
    for a in "xyz":
        assert (tmp_path / "py" / f"{a}.comp").read_text() == t[a]["text"]
    exe = os.environ.get("ABBE_EXE")
    if exe:
        subprocess.run([exe, "export", "linuxcnc", "--machine", str(MACHINE), "--at",
                        "-495,-250,-410", "--tool-length", "130", "-o", str(tmp_path / "cli")],
                       check=True, capture_output=True)
        for a in "xyz":
            assert (tmp_path / "cli" / f"{a}.comp").read_text() == t[a]["text"]


def test_linuxcnc_in_inch():
    m = abbe.Machine(MACHINE)
    mm = abbe.export_linuxcnc(m)["x"]["text"].splitlines()[0].split()
    inch = abbe.export_linuxcnc(m, units="inch")["x"]["text"].splitlines()[0].split()
    assert float(inch[0]) == pytest.approx(float(mm[0]) / 25.4, abs=1e-6)
    assert float(inch[1]) == pytest.approx(float(mm[1]) / 25.4, abs=1e-6)
    with pytest.raises(ValueError):
        abbe.export_linuxcnc(m, units="furlong")


def test_zero_machine_gives_zero_tables():
    m = abbe.Machine(ZERO)
    for model in ("htm", "ae-arm", "dual"):
        t = abbe.export_linuxcnc(m, model=model)
        for a in "xyz":
            assert not np.any(t[a]["forward_um"]) and not np.any(t[a]["reverse_um"])
    g = abbe.volumetric_grid(m, model="all", step=200)
    for e in g["models"].values():
        assert not np.any(e)


def test_grid_shape_and_csv(tmp_path):
    m = abbe.Machine(MACHINE)
    g = abbe.volumetric_grid(m, model="all", step=(100, 100, 100), tool_length=200,
                             output=tmp_path / "g.csv")
    n = len(g["x"]) * len(g["y"]) * len(g["z"])
    assert (len(g["x"]), len(g["y"]), len(g["z"])) == (11, 6, 6)
    assert g["z"][0] == -660 and g["z"][-1] == -200
    assert set(g["models"]) == {"htm", "ae-arm", "dual"}
    for e in g["models"].values():
        assert e.shape == (n, 3) and np.abs(e).max() > 1
    rows = (tmp_path / "g.csv").read_text().splitlines()
    assert len(rows) == n + 1
    last = [float(v) for v in rows[-1].split(",")]
    assert last[3:6] == pytest.approx(g["models"]["htm"][-1], abs=1e-6)
    with pytest.raises(ValueError, match="--step"):
        abbe.volumetric_grid(m, step=1e-9)
    with pytest.raises(ValueError):
        abbe.volumetric_grid(m, step=50, count=3)
