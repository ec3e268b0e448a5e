#!/usr/bin/env bash
# Starts the real ParaView GUI under Xvfb with the CraterKit plugin loaded as a user would
# (--plugins, the same path as Tools > Manage Plugins), plays gui_create_source.py and
# checks that GranularBed was found and produced particles. Catches a broken XML that
# pvbatch alone might not (the GUI parses the panel hints and domains).
set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
plugin_dir=$1
marker=$(mktemp)
trap 'rm -f "$marker"' EXIT
export CRATERKIT_GUI_MARKER=$marker LIBGL_ALWAYS_SOFTWARE=1
unset PYTHONHOME
# A fresh settings directory, so user settings cannot change the outcome.
export HOME=$(mktemp -d)
timeout 300 xvfb-run -a -s "-screen 0 1280x1024x24" \
  paraview --dr --plugin-search-paths="$plugin_dir" --plugins=CraterKit \
  --script="$here/gui_create_source.py" >"$marker.log" 2>&1 || true
cat "$marker.log"
echo "--- marker:"
cat "$marker"
grep -q "^prototype yes" "$marker" || { echo "FAIL: GranularBed is not registered in the GUI"; exit 1; }
points=$(awk '/^points/ {print $2}' "$marker")
[[ -n "$points" && "$points" -gt 0 ]] || { echo "FAIL: GranularBed produced no particles in the GUI"; exit 1; }
echo "1 passed, 0 failed"
