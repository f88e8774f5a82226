#!/bin/sh
# ctest wrapper of cantools_oracle.py: fails, saying what to do, when the Python venv is missing.
#   run_cantools_oracle.sh PYTHON VMASS_CAN DBC_DIR
python=$1 vmass_can=$2 dbc_dir=$3
if [ ! -x "$python" ]; then
  echo "cantools oracle: no Python at $python (VMASS_PYTHON)." >&2
  echo "Run scripts/install-python-deps.sh to create build/pyenv with cantools, or configure" >&2
  echo "with -DVMASS_PYTHON=/path/to/python that has cantools." >&2
  exit 1
fi
exec "$python" "$(dirname "$0")/cantools_oracle.py" --vmass-can "$vmass_can" --dbc-dir "$dbc_dir"
