#!/bin/sh
# The Python package from the source tree: `python -m build --wheel` makes the wheel (the CMake
# build of the extension kept in WORK/cmake-build, so that a second run compiles only what
# changed; ccache serves a fresh clone), and it installs into a fresh venv, WORK/venv, where the
# other tests/python tests import it. The venv sees the project venv's packages (numpy, pandas,
# pyarrow, Dask, python-can, asammdf, lcm) through a .pth file, so that nothing is downloaded;
# vmass itself comes from the wheel alone.
#   wheel_test.sh SOURCE_DIR PROJECT_PYTHON WORK
set -u
src=$1 pyenv_python=$2 work=$3
fail() { echo "wheel_test: FAIL: $*" >&2; exit 1; }

"$pyenv_python" -c "import build, scikit_build_core, nanobind" 2>/dev/null ||
  fail "$pyenv_python lacks build, scikit-build-core or nanobind: run scripts/install-python-deps.sh"
rm -rf "$work/dist" "$work/venv"
mkdir -p "$work"
"$pyenv_python" -m build --wheel --no-isolation --outdir "$work/dist" \
  -Cbuild-dir="$work/cmake-build" "$src" >"$work/build.log" 2>&1 ||
  { tail -40 "$work/build.log"; fail "python -m build --wheel"; }
wheel=$(ls "$work"/dist/vmass-*.whl) || fail "no wheel in $work/dist"
for member in vmass/__init__.py vmass/replay.py vmass/fleet/__main__.py vmass/_vmass. \
              vmass/lcmtypes/mass_estimate_t.py vmass/log_convert.py; do
  "$pyenv_python" -m zipfile -l "$wheel" | grep -q "$member" || fail "$member not in $wheel"
done

/usr/bin/python3 -m venv "$work/venv" || fail "python3 -m venv"
site=$("$pyenv_python" -c "import sysconfig; print(sysconfig.get_paths()['purelib'])")
venv_site=$("$work/venv/bin/python" -c "import sysconfig; print(sysconfig.get_paths()['purelib'])")
echo "$site" >"$venv_site/vmass-test-dependencies.pth"
"$work/venv/bin/python" -m pip install --quiet --disable-pip-version-check --no-index --no-deps \
  "$wheel" || fail "pip install $wheel"
cd "$work" || exit 1  # not the source tree: the installed package is imported
"$work/venv/bin/python" - "$work/venv" <<'PY' || fail "the installed package"
import sys
import vmass
import vmass.fleet
assert vmass.__file__.startswith(sys.argv[1]), vmass.__file__
assert vmass.mass_estimate_t.__name__ == "mass_estimate_t"
print("wheel_test: vmass", vmass.__version__, "installed from the wheel at", vmass.__file__)
PY
