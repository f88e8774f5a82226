#!/usr/bin/env bash
# Makes the Python virtual environment the test oracles, benchmarks and the log converter use
# (build/pyenv) and installs their packages into it: cantools (the independent DBC decoder the
# CAN layer is checked against), python-can and asammdf (vmass-log-convert reads BLF and MDF4
# with them; the tests write ASC, TRC, BLF and MDF4 with them), lcm (the Python LCM bindings
# the Python subscriber test uses; Debian 12 has no python3-lcm), and what the Python package
# vmass needs to build and run (tests/python). Idempotent: an existing venv is reused, and pip is not run when every package is
# already importable. Needs /usr/bin/python3 with the venv module (Debian: python3-venv).
#
#   scripts/install-python-deps.sh [VENV_DIR]     (default: <repo>/build/pyenv)
set -euo pipefail

repo=$(cd "$(dirname "$0")/.." && pwd)
venv=${1:-$repo/build/pyenv}
python=/usr/bin/python3
packages=(cantools python-can asammdf lcm)
modules=(cantools can asammdf lcm)
# The Python package vmass (pyproject.toml): its build (scikit-build-core, nanobind, build) and
# what it runs with (pandas, pyarrow, Dask), for tests/python.
packages+=(scikit-build-core nanobind build pandas pyarrow "dask[distributed]")
modules+=(scikit_build_core nanobind build pandas pyarrow dask distributed)

if [ ! -x "$venv/bin/python" ]; then
  echo "install-python-deps: creating $venv"
  mkdir -p "$(dirname "$venv")"
  "$python" -m venv "$venv"
fi

missing=0
for m in "${modules[@]}"; do
  "$venv/bin/python" -c "import $m" 2>/dev/null || missing=1
done
if [ "$missing" -eq 0 ]; then
  echo "install-python-deps: ${packages[*]} present in $venv"
  exit 0
fi

echo "install-python-deps: installing ${packages[*]} into $venv"
"$venv/bin/python" -m pip install --quiet --disable-pip-version-check "${packages[@]}"
"$venv/bin/python" -c "import cantools, can, asammdf; print('install-python-deps: cantools',
  cantools.__version__, 'python-can', can.__version__, 'asammdf', asammdf.__version__)"
