#!/usr/bin/env bash
# Installs the Debian packages abbe needs.
#   tools/install-deps.sh          what the build and the main job need
#                                  (compiler, CMake, the libraries)
#   tools/install-deps.sh --test   adds the test tools: GoogleTest, clang for
#                                  the fuzzer, the browsers of the report test,
#                                  pybind11/NumPy/pytest for the Python module,
#                                  and LinuxCNC's rs274 for the interop test
#                                  (linuxcnc-uspace unpacked, not installed,
#                                  under $ABBE_LINUXCNC_DIR, default
#                                  /opt/abbe/linuxcnc; its runtime library
#                                  libboost-python installed)
# The tests download and install nothing themselves; they use what this
# script put in place (docs/dependencies.md says why each package is there).
# Idempotent and non-interactive: packages already present are not touched.
set -euo pipefail

with_test=0
for a in "$@"; do
  case "$a" in
    --test) with_test=1 ;;
    -h|--help) sed -n '2,15p' "$0" | sed 's/^# \{0,1\}//'; exit 0 ;;
    *) echo "install-deps: unknown option $a (usage: tools/install-deps.sh [--test])" >&2; exit 2 ;;
  esac
done

packages=(
  build-essential cmake ninja-build ccache pkg-config
  libboost-dev libeigen3-dev libspdlog-dev libfmt-dev libyaml-cpp-dev
  libcli11-dev nlohmann-json3-dev
)
if [ $with_test = 1 ]; then
  packages+=(
    libgtest-dev libgmock-dev libbenchmark-dev
    clang libclang-rt-14-dev            # libFuzzer target and its sanitizers
    libboost-python1.74.0               # runtime of LinuxCNC's rs274 (interop test)
    time                                # /usr/bin/time for peak-RSS measurements
    chromium firefox-esr python3        # browser test: headless screenshots, PNG checks
    bsdutils                            # `script` (pseudo-terminal) for the progress-bar test
    pybind11-dev python3-dev python3-numpy python3-pytest  # Python module and its tests
  )
fi

SUDO=""
if [ "$(id -u)" -ne 0 ]; then SUDO="sudo"; fi
export DEBIAN_FRONTEND=noninteractive

missing=()
for p in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done
if [ ${#missing[@]} -eq 0 ]; then
  echo "install-deps: all ${#packages[@]} packages present"
else
  echo "install-deps: installing ${missing[*]}"
  $SUDO apt-get update -qq
  $SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
fi

# LinuxCNC's standalone interpreter for the interop test and the benchmark:
# the package linuxcnc-uspace is unpacked (dpkg -x), not installed (it would
# pull in a realtime stack the tests do not need).
if [ $with_test = 1 ]; then
  lcnc=${ABBE_LINUXCNC_DIR:-/opt/abbe/linuxcnc}
  if [ -x "$lcnc/usr/bin/rs274" ]; then
    echo "install-deps: rs274 present in $lcnc"
  else
    echo "install-deps: unpacking linuxcnc-uspace into $lcnc (apt-get download, ~21 MB)"
    tmp=$(mktemp -d)
    chmod 755 "$tmp"   # apt-get download runs as _apt
    trap 'rm -rf "$tmp"' EXIT
    (cd "$tmp" && apt-get download linuxcnc-uspace >/dev/null)
    $SUDO mkdir -p "$(dirname "$lcnc")"
    $SUDO rm -rf "$lcnc.tmp"
    $SUDO dpkg -x "$tmp"/linuxcnc-uspace_*.deb "$lcnc.tmp"
    dpkg-deb -f "$tmp"/linuxcnc-uspace_*.deb Version | $SUDO tee "$lcnc.tmp/VERSION" >/dev/null
    $SUDO mv "$lcnc.tmp" "$lcnc"
  fi
fi
