#!/usr/bin/env bash
# Installs the Debian 12 packages Palpa needs to build and test.
# Idempotent: packages already installed are skipped; works as root or through sudo.
set -euo pipefail

# What the current tree builds with (ui/ and app/gui: Qt 5, VTK 9, Xvfb for their tests).
# device/: hidapi (SpaceMouse) and libusb (Falcon), found through pkg-config.
packages=(
  build-essential cmake ninja-build python3 python3-jsonschema
  ccache  # compiler cache (cmake/Ccache.cmake): a second build of the same sources is mostly cache hits
  libeigen3-dev nlohmann-json3-dev libcli11-dev libfmt-dev
  libnanoflann-dev  # k-d tree: the search pattern's nearest points between strips (core/score)
  libgtest-dev libgmock-dev libbenchmark-dev
  libopencv-dev libsqlite3-dev sqlite3
  qtbase5-dev libvtk9-dev libvtk9-qt-dev xvfb xauth
  libxcb1-dev xdotool  # app/gui watches its X windows (xcb DestroyNotify); test_gui_signal.py destroys one with xdotool
  pkg-config libhidapi-dev libusb-1.0-0-dev
  postgresql libpq-dev  # store/: the centre store (libpq; the server for its tests)
  libcurl4-openssl-dev  # lrs/: xAPI statements to a learning record store
  libssl-dev zlib1g-dev  # SHA-256 (store/, anatomy_io/) and gzip (sessions, NIfTI and NRRD), named rather than left to other packages' dependencies
  desktop-file-utils  # packaging test: desktop-file-validate on the menu entry (dpkg-dev comes with build-essential)
  gmsh calculix-ccx python3-numpy python3-scipy  # the finite-element reference (tools/fem) and its tests
  clang libclang-rt-14-dev  # the fuzz targets: libFuzzer with ASan + UBSan (scripts/fuzz.sh)
)

missing=()
for p in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q '^install ok installed$'; then
    missing+=("$p")
  fi
done

if [ ${#missing[@]} -eq 0 ]; then
  echo "install-deps: all ${#packages[@]} packages already installed"
  exit 0
fi

if [ "$(id -u)" -eq 0 ]; then
  sudo=()
elif command -v sudo >/dev/null 2>&1; then
  # -n: fail with a message instead of waiting for a password nobody can type (CI).
  if [ -t 0 ]; then sudo=(sudo); else sudo=(sudo -n); fi
else
  echo "install-deps: need root or sudo to install: ${missing[*]}" >&2
  exit 1
fi

echo "install-deps: installing ${missing[*]}"
export DEBIAN_FRONTEND=noninteractive
# A fresh machine may still be running unattended upgrades: wait for the dpkg lock.
apt_opts=(-o DPkg::Lock::Timeout=600)
"${sudo[@]}" apt-get "${apt_opts[@]}" update -qq
"${sudo[@]}" env DEBIAN_FRONTEND=noninteractive apt-get "${apt_opts[@]}" install -y -qq --no-install-recommends "${missing[@]}"
