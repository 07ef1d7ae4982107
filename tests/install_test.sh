#!/usr/bin/env bash
# The installed tree works: `cmake --install` into a fresh prefix gives the
# command, the Python package and the CMake package; a project outside the
# source tree finds it with find_package(fit3dof), links fit3dof::core and
# fits a config to the same Cm_alpha as the command.
#
#   tests/install_test.sh BUILD_DIR SOURCE_DIR
set -euo pipefail
build="$1"
source="$2"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
prefix="$work/prefix"

cmake --install "$build" --prefix "$prefix" >/dev/null
for f in bin/fit3dof include/fit3dof/fit.h include/fit3dof/config.h \
         include/fit3dof/version.h; do
  [ -e "$prefix/$f" ] || { echo "not installed: $f"; exit 1; }
done
ls "$prefix"/lib*/libfit3dof.a >/dev/null
ls "$prefix"/lib*/cmake/fit3dof/fit3dofConfig.cmake >/dev/null
ls "$prefix"/lib*/cmake/fit3dof/fit3dofConfigVersion.cmake >/dev/null

# The command runs from the prefix.
version="$("$prefix/bin/fit3dof" --version)"
echo "$version"

# The Python package from the prefix (Debian's python3).
python_dir="$(ls -d "$prefix"/lib/python3*/dist-packages)"
PYTHONPATH="$python_dir" /usr/bin/python3 -c "
import fit3dof, sys
assert fit3dof.__file__.startswith('$prefix'), fit3dof.__file__
assert 'fit3dof ' + fit3dof.__version__ == '$version', fit3dof.__version__
print('python', fit3dof.__version__, fit3dof.__file__)
"

# A consumer project against the installed package only.
cmake -S "$source/tests/consumer" -B "$work/consumer" \
  -DCMAKE_PREFIX_PATH="$prefix" -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build "$work/consumer" >/dev/null
config="$source/configs/report/table6_sigma0.01.yaml"
out="$("$work/consumer/consumer" "$config")"
echo "$out"
"$prefix/bin/fit3dof" fit "$config" --out_dir="$work/cli" >/dev/null
expected="$(/usr/bin/python3 -c "
import json
print('%.17g' % json.load(open('$work/cli/report.json'))['parameters']['Cm_alpha']['value'])")"
case "$out" in
  *"Cm_alpha = $expected "*) echo "consumer equals the command: $expected" ;;
  *) echo "consumer gave: $out, the command: $expected"; exit 1 ;;
esac
