#!/usr/bin/env bash
# Installs the Debian packages earc needs that are missing, and nothing else.
# Idempotent and quick when everything is present (one dpkg query).
#   tools/setup.sh            build and run dependencies
#   tools/setup.sh --tests    also what the tests use (python3-pytest for the
#                             Python module's, chromium and jq for the viewer tests,
#                             clang for the fuzz targets, strace for the
#                             socket test, faketime for --deterministic's,
#                             postgresql for the PostgreSQL store's tests)
set -euo pipefail

packages=(
  build-essential cmake ninja-build pkg-config
  libsqlite3-dev sqlite3 libpq-dev libnanoflann-dev libeigen3-dev libfcl-dev libompl-dev
  libboost-serialization-dev libboost-filesystem-dev
  libcli11-dev doctest-dev nlohmann-json3-dev
  python3 python3-numpy python3-matplotlib librsvg2-bin
  pybind11-dev python3-pybind11 python3-dev
)
if [[ "${1:-}" == "--tests" ]]; then
  packages+=(chromium jq clang libclang-rt-14-dev strace faketime python3-pytest postgresql)
fi

missing=()
for p in "${packages[@]}"; do
  status=$(dpkg-query -W -f='${Status}' "$p" 2>/dev/null || true)
  [[ "$status" == "install ok installed" ]] || missing+=("$p")
done

if ((${#missing[@]} == 0)); then
  exit 0
fi

echo "setup: installing ${missing[*]}" >&2
if [[ $(id -u) -ne 0 ]]; then
  SUDO=sudo
else
  SUDO=
fi
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -qq
$SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
