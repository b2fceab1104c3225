#!/usr/bin/env python3
"""Interaction test of the 3-D toolpath of a predict report in headless
Chromium, driven through the DevTools protocol (tests/browser/cdp.py) with
real input events:

  interaction.py CHROMIUM REPORT.html [--id toolpath-3d]

- the page loads without console errors, the view reports ready and the
  canvas holds drawn (non-white) pixels;
- rotate: a mouse drag of (+100, +40) px turns the view by -50 deg yaw and
  +20 deg pitch (the state the page writes into data- attributes), and the
  picture changes;
- zoom: the wheel zooms in;
- hover: moving the mouse onto the drawn point of the largest |d| shows the
  tooltip with that point's source line and |d|, which are the "at line"
  and "max |d|" of the summary table's "all" row (the decimation keeps the extremes);
- tolerance: a tolerance above every |d| leaves no point above it, one
  below every |d| puts all points above it.
Prints what it checked; exit 0 when all passed, 1 otherwise.
"""
import argparse
import os
import re
import shutil
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from cdp import Chromium  # noqa: E402

failures = []


def check(ok, what):
    print(("ok   " if ok else "FAIL ") + what)
    if not ok:
        failures.append(what)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("chromium")
    ap.add_argument("report")
    ap.add_argument("--id", default="toolpath-3d")
    a = ap.parse_args()
    profile = tempfile.mkdtemp()
    b = Chromium(a.chromium, profile)
    try:
        run(b, os.path.abspath(a.report), a.id)
    finally:
        b.close()
        shutil.rmtree(profile, ignore_errors=True)
    if failures:
        print(f"{len(failures)} failure(s)")
        return 1
    print("interaction test passed")
    return 0


def state(b, fid):
    return b.eval(f"Object.assign({{}}, document.getElementById('{fid}').dataset)")


def canvas_ink(b, fid):
    """Share of non-white pixels of the canvas and a checksum of them."""
    return b.eval(f"""(function () {{
      var c = document.querySelector('#{fid} canvas'), x = c.getContext('2d');
      var d = x.getImageData(0, 0, c.width, c.height).data, ink = 0, sum = 0;
      for (var i = 0; i < d.length; i += 4)
        if (d[i] < 250 || d[i + 1] < 250 || d[i + 2] < 250) {{ ink++; sum = (sum * 31 + d[i] + i) % 1000000007; }}
      return [ink / (d.length / 4), sum];
    }})()""")


def run(b, path, fid):
    b.open_page()
    b.navigate("file://" + path)
    check(b.eval(f"document.getElementById('{fid}') !== null"), f"figure #{fid} present")
    s = state(b, fid)
    check(s.get("ready") == "true", "the 3-D view initialised (data-ready)")
    ink, sum0 = canvas_ink(b, fid)
    check(ink > 0.002, f"the canvas shows the path ({100 * ink:.2f} % of its pixels drawn)")
    b.eval(f"document.getElementById('{fid}').scrollIntoView()")
    rect = b.eval(f"(function () {{ var r = document.querySelector('#{fid} canvas')"
                  ".getBoundingClientRect(); return [r.left, r.top, r.width, r.height]; })()")
    left, top, w, h = rect
    check(w > 100 and h > 100 and top >= 0, f"canvas on screen at ({left:.0f}, {top:.0f}), {w:.0f} x {h:.0f}")

    # Rotate: drag from a corner region (nothing picked there matters).
    yaw0, pitch0, draws0 = float(s["yaw"]), float(s["pitch"]), int(s["draws"])
    x0, y0 = left + 0.2 * w, top + 0.3 * h
    b.mouse("mouseMoved", x0, y0)
    b.mouse("mousePressed", x0, y0, buttons=1, button="left")
    for k in range(1, 5):
        b.mouse("mouseMoved", x0 + 25 * k, y0 + 10 * k, buttons=1, button="left")
    b.mouse("mouseReleased", x0 + 100, y0 + 40, button="left")
    s = state(b, fid)
    yaw1, pitch1 = float(s["yaw"]), float(s["pitch"])
    want_pitch = max(-90.0, min(90.0, pitch0 + 20.0))
    check(abs(yaw1 - (yaw0 - 50.0)) < 0.11 and abs(pitch1 - want_pitch) < 0.11,
          f"drag rotates: yaw {yaw0} -> {yaw1}, pitch {pitch0} -> {pitch1}")
    check(int(s["draws"]) > draws0, "the view was redrawn while dragging")
    ink1, sum1 = canvas_ink(b, fid)
    check(sum1 != sum0 and ink1 > 0.002, "the rotated picture differs from the first")

    # Zoom with the wheel.
    zoom0 = float(s["zoom"])
    b.mouse("mouseWheel", left + w / 2, top + h / 2, delta_y=-240)
    s = state(b, fid)
    check(float(s["zoom"]) > 1.5 * zoom0, f"wheel zooms in: {zoom0} -> {s['zoom']}")
    b.eval(f"document.querySelector('#{fid} button[data-view=iso]').click()")

    # Hover over the drawn point of the largest |d|.
    i = b.eval(f"abbeViews['{fid}'].largest()")
    px, py = b.eval(f"abbeViews['{fid}'].project({i})")
    b.mouse("mouseMoved", px, py)
    s = state(b, fid)
    tip = b.eval(f"document.getElementById('{fid}-tip').textContent")
    visible = b.eval(f"getComputedStyle(document.getElementById('{fid}-tip')).display")
    check(s.get("hover") not in (None, "-1") and visible == "block",
          f"hover at ({px:.0f}, {py:.0f}) shows the tooltip (point {s.get('hover')})")
    m = re.search(r"line (\d+):.*\|d\| = ([0-9.]+)", tip, re.S)
    check(m is not None, f"the tooltip names the line and |d|: {tip!r}")
    model = b.eval(f"document.getElementById('{fid}-model').value")
    row = b.eval("(function () { var rows = document.querySelectorAll('#summary-table tr');"
                 " for (var i = 1; i < rows.length; i++) { var c = rows[i].cells;"
                 f" if (c[0].textContent === '{model}' && c[1].textContent === 'all')"
                 " return [c[7].textContent, c[8].textContent]; }"
                 " return null; })()")
    if m and row:
        check(m.group(1) == row[1] and abs(float(m.group(2)) - float(row[0])) < 0.0015,
              f"hovered line {m.group(1)}, |d| {m.group(2)} um = the table's max |d| "
              f"{row[0]} um at line {row[1]} ({model})")
    else:
        check(False, "summary table row of the model found")
    b.mouse("mouseMoved", left + 2, top + 2)

    # Tolerance: recolouring and the count of points above it.
    n = b.eval(f"abbeViews['{fid}'].count")

    def set_tol(v):
        b.eval(f"(function () {{ var e = document.getElementById('{fid}-tol'); e.value = '{v}';"
               " e.dispatchEvent(new Event('input')); })()")
        return int(state(b, fid)["above"])
    check(set_tol(1e9) == 0, "a tolerance above every |d|: no point above it")
    check(set_tol(1e-9) == n, f"a tolerance below every |d|: all {n} points above it")
    errs = b.errors()
    check(not errs, "no console errors or uncaught exceptions" + (f": {errs}" if errs else ""))


if __name__ == "__main__":
    sys.exit(main())
