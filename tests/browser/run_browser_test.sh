#!/usr/bin/env bash
# Browser test of the HTML reports (ctest label "browser", docs/report.md):
# generates the predict, map, diagnose, compensate and iso230 reports,
# renders each in headless Chromium and in headless Firefox ESR, keeps the
# screenshots (WORK/<name>.png, WORK/<name>.firefox.png) as test artifacts,
# and fails on Chromium console errors, when the expected plots are missing
# from the rendered DOM, when a screenshot is blank or of the wrong size, or
# when Firefox lays the page out differently from Chromium
# (tests/browser/png_compare.py). Then drives the 3-D toolpath of the
# predict report with real mouse events over the DevTools protocol
# (tests/browser/interaction.py: rotate, zoom, hover, tolerance).
# Installs nothing: the browsers come from tools/install-deps.sh --test;
# without chromium the test is skipped (exit code 77), without firefox-esr
# the Firefox comparison is. ABBE_SKIP_BROWSER=1 skips it.
#
# usage: run_browser_test.sh ABBE SOURCE_DIR WORK_DIR
set -u
abbe=$(realpath "$1")
src=$(realpath "$2")
work=$(realpath -m "$3")  # file:// URLs need absolute paths

if [ "${ABBE_SKIP_BROWSER:-0}" = 1 ]; then
  echo "ABBE_SKIP_BROWSER=1: skipped"
  exit 77
fi

browser=$(command -v chromium || command -v chromium-browser || true)
if [ -z "$browser" ]; then
  echo "chromium is not installed (tools/install-deps.sh --test installs it): skipped"
  exit 77
fi
echo "browser: $("$browser" --version 2>/dev/null)"
firefox=$(command -v firefox-esr || command -v firefox || true)
if [ -n "$firefox" ]; then
  echo "browser: $("$firefox" --version 2>/dev/null)"
else
  echo "firefox-esr is not installed (tools/install-deps.sh --test): no Firefox comparison"
fi
width=1400
height=3000

rm -rf "$work"
mkdir -p "$work"
failures=0
fail() {
  echo "FAIL: $*"
  failures=$((failures + 1))
}

machine="$src/tests/data/machines/sample.yaml"
"$abbe" -q report predict "$src/nc-samples/thesis-toolpath-1.ngc" --machine "$machine" \
  --model all -o "$work/predict.html" || fail "abbe report predict exited with $?"
"$abbe" -q report map --machine "$machine" --grid 100 -o "$work/map.html" ||
  fail "abbe report map exited with $?"
"$abbe" -q compensate "$src/nc-samples/thesis-toolpath-1.ngc" --machine "$machine" \
  -o "$work/compensated.ngc" || fail "abbe compensate exited with $?"
"$abbe" -q report compensate "$src/nc-samples/thesis-toolpath-1.ngc" \
  --compensated "$work/compensated.ngc" --machine "$machine" -o "$work/compensate.html" ||
  fail "abbe report compensate exited with $?"

run_browser() {  # run_browser PROFILE_DIR ARGS...
  local profile=$1
  shift
  timeout 180 "$browser" --headless --no-sandbox --disable-gpu --disable-quic --no-first-run \
    --disable-background-networking --disable-component-update --disable-sync \
    --hide-scrollbars --user-data-dir="$profile" "$@"
}

check_page() {  # check_page NAME ID...
  local name=$1
  shift
  local page="$work/$name.html"
  [ -s "$page" ] || { fail "$name: no report written"; return; }
  local profile
  profile=$(mktemp -d)
  run_browser "$profile" --enable-logging=stderr --v=0 --window-size=$width,$height \
    --screenshot="$work/$name.png" "file://$page" >"$work/$name.screenshot.log" 2>&1
  local rc=$?
  rm -rf "$profile"
  [ $rc = 0 ] || fail "$name: chromium --screenshot exited with $rc (see $work/$name.screenshot.log)"
  if [ ! -s "$work/$name.png" ] || [ "$(stat -c %s "$work/$name.png")" -lt 20000 ]; then
    fail "$name: the screenshot is missing or nearly empty"
  fi
  python3 "$src/tests/browser/png_compare.py" size "$work/$name.png" $width $height ||
    fail "$name: the Chromium screenshot is blank or of the wrong size"
  # Firefox ESR: the same page, the same window; a fresh profile and HOME.
  [ -n "$firefox" ] && check_firefox "$name"
  if grep -E "Uncaught|ERROR:CONSOLE|CONSOLE\([0-9]+\).*[Ee]rror|Not allowed to load" \
      "$work/$name.screenshot.log"; then
    fail "$name: console errors while loading the page"
  fi
  check_dom "$@"
}

check_firefox() {  # check_firefox NAME
  local name=$1 page="$work/$1.html" rc
  local ff_home
  ff_home=$(mktemp -d)
  HOME=$ff_home timeout 180 "$firefox" --headless --no-remote --profile "$ff_home" \
    --screenshot "$work/$name.firefox.png" --window-size=$width,$height "file://$page" \
    >"$work/$name.firefox.log" 2>&1
  rc=$?
  rm -rf "$ff_home"
  [ $rc = 0 ] || fail "$name: firefox --screenshot exited with $rc (see $work/$name.firefox.log)"
  if python3 "$src/tests/browser/png_compare.py" size "$work/$name.firefox.png" $width $height; then
    python3 "$src/tests/browser/png_compare.py" same "$work/$name.png" "$work/$name.firefox.png" ||
      fail "$name: Firefox lays the page out differently from Chromium"
  else
    fail "$name: the Firefox screenshot is missing, blank or of the wrong size"
  fi
}

check_dom() {  # check_dom ID... (NAME and page from check_page)
  local profile
  profile=$(mktemp -d)
  run_browser "$profile" --dump-dom "file://$page" >"$work/$name.dom.html" 2>"$work/$name.dom.log"
  rm -rf "$profile"
  local id
  for id in "$@"; do
    grep -q "id=\"$id\"" "$work/$name.dom.html" || fail "$name: plot or table '$id' not in the DOM"
  done
  # The page's script ran: it fills the table of contents and the plot count.
  grep -q '<a href="#summary">\|<a href="#map-summary">\|<a href="#iso230-summary">' "$work/$name.dom.html" ||
    fail "$name: the table of contents was not built (script did not run)"
  grep -Eq 'id="plot-count">[1-9][0-9]* plots<' "$work/$name.dom.html" ||
    fail "$name: the plot count was not filled in (script did not run)"
  if grep -Eiq '="[^"]*\bnan\b' "$work/$name.dom.html"; then
    fail "$name: NaN in an attribute"
  fi
  echo "$name: $(grep -o '<svg ' "$work/$name.dom.html" | wc -l) plots, screenshot $work/$name.png"
}

check_page predict summary-table toolpath-3d toolpath-3d-tol provenance \
  deviation-models deviation-htm deviation-ae-arm deviation-dual
# The 3-D toolpath: rotate, zoom, hover, tolerance, with real input events.
python3 "$src/tests/browser/interaction.py" "$browser" "$work/predict.html" ||
  fail "predict: the 3-D toolpath interaction test failed"
"$abbe" -q report iso230 "$src/machines/sample/runs.csv" -o "$work/iso230.html" ||
  fail "abbe report iso230 exited with $?"
check_page iso230 iso230-table iso230-x-exx iso230-x-eyx provenance
"$abbe" -q report diagnose --measured "$src/machines/sample/measured-grid.csv" \
  --machine "$src/machines/sample/machine.yaml" -o "$work/diagnose.html" ||
  fail "abbe report diagnose exited with $?"
check_page diagnose diagnose-models diagnose-effects residual-x residual-y residual-z residual-t
check_page compensate compensate-table compensate-iso compensate-xy compensate-xz compensate-yz \
  compensate-deviation
check_page map map-table map-htm-xy0 map-ae-arm-xy0 map-htm-xz3 map-ae-arm-yz5

if [ "$failures" -gt 0 ]; then
  echo "$failures failure(s)"
  exit 1
fi
echo "browser test passed"
