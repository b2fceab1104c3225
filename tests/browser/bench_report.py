#!/usr/bin/env python3
"""Benchmark of the predict report's size and rendering time (docs/performance.md).

  bench_report.py ABBE GEN_PROGRAM CHROMIUM [BLOCKS...]   (default 30000 1000000)

For each size: gen_program --blocks N --seed 1 writes a program, `abbe report
predict --model all` on the sample machine writes its report (wall time of
abbe printed too), and headless Chromium loads the report over the DevTools
protocol (tests/browser/cdp.py), best of 3: the time from the navigation
to the first frame after the 3-D view is drawn (performance.now() after two
animation frames, i.e. parse + scripts + layout + paint), the wall time of
the same, and the 3-D view's own initialisation time. The 23-line
thesis-toolpath-1.ngc is measured first. Nothing is installed; the browser
comes from tools/install-deps.sh --test.
"""
import os
import shutil
import subprocess
import sys
import tempfile
import time

here = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, here)
from cdp import Chromium  # noqa: E402

src = os.path.dirname(os.path.dirname(here))


def report(abbe, program, out):
    t = time.monotonic()
    subprocess.run([abbe, "-q", "report", "predict", program, "--machine",
                    os.path.join(src, "machines/sample/machine.yaml"), "--model", "all",
                    "-o", out], check=True)
    return time.monotonic() - t


def render(browser, page, repeat=3):
    best = None
    for _ in range(repeat):
        profile = tempfile.mkdtemp()
        b = Chromium(browser, profile)
        try:
            b.open_page()
            t = time.monotonic()
            b.navigate("file://" + page)
            first_frame = b.eval(
                "new Promise(r => requestAnimationFrame(() => requestAnimationFrame("
                "() => r(performance.now()))))", await_promise=True)
            wall = time.monotonic() - t
            init = b.eval("(document.querySelector('figure.toolpath-3d') || {dataset: {}})"
                          ".dataset.initMs")
            errors = b.errors()
        finally:
            b.close()
            shutil.rmtree(profile, ignore_errors=True)
        if errors:
            raise SystemExit(f"{page}: console errors {errors}")
        r = (first_frame / 1000.0, wall, float(init or "nan") / 1000.0)
        if best is None or r[0] < best[0]:
            best = r
    return best


def main():
    if len(sys.argv) < 4:
        raise SystemExit(__doc__)
    abbe, gen, browser = sys.argv[1:4]
    sizes = [int(s) for s in sys.argv[4:]] or [30000, 1000000]
    work = tempfile.mkdtemp(prefix="abbe-bench-report-")
    print(f"{'program':>28} {'report MB':>9} {'abbe s':>7} {'first frame s':>13} "
          f"{'wall s':>7} {'3-D init s':>10}")
    programs = [("thesis-toolpath-1.ngc", os.path.join(src, "nc-samples/thesis-toolpath-1.ngc"))]
    for n in sizes:
        p = os.path.join(work, f"gen-{n}.ngc")
        subprocess.run([gen, "--blocks", str(n), "--seed", "1", "-o", p], check=True)
        programs.append((f"gen_program {n} blocks", p))
    for name, p in programs:
        out = os.path.join(work, os.path.basename(p) + ".html")
        t_abbe = report(abbe, p, out)
        size = os.path.getsize(out) / 1e6
        ff, wall, init = render(browser, out)
        print(f"{name:>28} {size:9.3f} {t_abbe:7.1f} {ff:13.3f} {wall:7.3f} {init:10.3f}",
              flush=True)
    shutil.rmtree(work, ignore_errors=True)


if __name__ == "__main__":
    main()
