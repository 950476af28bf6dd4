#!/usr/bin/env bash
# Installs the build in $1 to a temporary prefix, moves the prefix, and checks from another folder that the installed
# waam says its version, finds its data under the moved prefix (not the source tree) and plans and checks a scenario.
set -euo pipefail
build=$1
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cmake --install "$build" --prefix "$work/first" >/dev/null
mv "$work/first" "$work/moved"
mkdir -p "$work/elsewhere"
cd "$work/elsewhere"
unset WAAM_DATA_DIR
version=$("$work/moved/bin/waam" --version)
echo "$version"
grep -q "^waam [0-9][0-9.]* (commit " <<<"$version" || { echo "FAIL: --version says '$version'"; exit 1; }
grep -qx "data: $work/moved/share/waam-twin" <<<"$version" || { echo "FAIL: data not under the moved prefix"; exit 1; }
"$work/moved/bin/waam" check "$work/moved/share/waam-twin/scenarios/cell/cell_ok.yaml" -o out -q --no-images \
  || { echo "FAIL: the installed waam could not check an installed scenario"; exit 1; }
test -s out/check.json || { echo "FAIL: no check.json"; exit 1; }
# The library of cells is installed data too: a URDF preset found under the moved prefix.
"$work/moved/bin/waam" check "$work/moved/share/waam-twin/scenarios/cell/preset_yaskawa_mh12.yaml" -o preset -q \
  --no-images || { echo "FAIL: the installed waam could not check a preset cell"; exit 1; }
grep -q '"source": *"yaskawa_mh12"' preset/check.json || { echo "FAIL: the preset is not named in check.json"; exit 1; }
if [ -f /usr/share/javascript/three/three.min.js ]; then
  # The viewer's template is installed data too.
  "$work/moved/bin/waam" check "$work/moved/share/waam-twin/scenarios/cell/cell_ok.yaml" -o viewer -q --no-program \
    || { echo "FAIL: the installed waam could not write the viewer"; exit 1; }
  test -s viewer/viewer.html || { echo "FAIL: no viewer.html"; exit 1; }
fi
# The Python package, when it was built: imported from the moved prefix, it finds the data there too.
package="$work/moved/lib/python3/dist-packages"
if [ -d "$package/waam_twin" ]; then
  test -f "$package/waam_twin/py.typed" -a -f "$package/waam_twin/_core.pyi" || { echo "FAIL: no stubs"; exit 1; }
  PYTHONPATH="$package" /usr/bin/python3 -c "
import sys, waam_twin as wt
assert wt.__file__.startswith('$work/moved/'), wt.__file__
assert wt.data_dir() == '$work/moved/share/waam-twin', wt.data_dir()
plan = wt.plan(wt.load_scenario('$work/moved/share/waam-twin/scenarios/cell/cell_ok.yaml'))
assert plan.layer_count > 0
" || { echo "FAIL: the installed Python package"; exit 1; }
fi
echo "installed, moved and ran from $work/elsewhere"
