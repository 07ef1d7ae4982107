#!/usr/bin/env bash
# tools/plot and python3 -m fit3dof.plot on real fit, diagnose and batch
# directories: every figure a real PNG.
#
#   tests/plot_tool_test.sh FIT3DOF_BINARY SOURCE_DIR
set -euo pipefail
bin="$1"
root="$2"
out="$(mktemp -d)"
trap 'rm -rf "$out"' EXIT

png() {  # a non-trivial PNG
  local f="$1"
  [ -s "$f" ] || { echo "missing $f"; exit 1; }
  head -c 8 "$f" | od -An -c | grep -q "P   N   G" || { echo "$f is not a PNG"; exit 1; }
  [ "$(stat -c %s "$f")" -gt 20000 ] || { echo "$f is suspiciously small"; exit 1; }
}

# A fit: motion (phi, theta, psi), residuals, psi-theta plane, coefficients.
"$bin" fit "$root/configs/report/table6_sigma0.02.yaml" --out_dir="$out/fit" >/dev/null 2>&1
"$root/tools/plot" "$out/fit" >/dev/null
for kind in motion residuals psi_theta; do
  png "$out/fit/table6-sigma0.02_$kind.png"
done
png "$out/fit/coefficients.png"

# The module draws the same figures.
rm "$out"/fit/*.png
(cd "$out" && PYTHONPATH="$root/python" /usr/bin/python3 -m fit3dof.plot fit >/dev/null)
png "$out/fit/table6-sigma0.02_motion.png"
png "$out/fit/coefficients.png"

# A diagnose directory: every step drawn, and the steps side by side.
"$bin" diagnose "$root/configs/report/table6_sigma0.02.yaml" --out_dir="$out/diagnose" >/dev/null 2>&1 || true
"$root/tools/plot" "$out/diagnose" >/dev/null
png "$out/diagnose/step0/table6-sigma0.02_residuals.png"
if ls -d "$out"/diagnose/step1 >/dev/null 2>&1; then
  png "$out/diagnose/steps.png"
fi

# A batch: every run, and the campaign figure against a config key.
"$bin" batch "$root/configs/examples/campaign/manifest.yaml" --out_dir="$out/batch" >/dev/null 2>&1
"$root/tools/plot" "$out/batch" --against flow.dynamic_pressure >/dev/null
png "$out/batch/campaign.png"
png "$out/batch/q150-a/q150-a_motion.png"
png "$out/batch/q450-c/coefficients.png"
# A key that is not in the configs: a clear error.
set +e
"$root/tools/plot" "$out/batch" --against flow.no_such_key >/dev/null 2>"$out/err"
status=$?
set -e
[ "$status" -ne 0 ] && grep -q "flow.no_such_key" "$out/err" || { echo "bad --against accepted"; exit 1; }

# A directory with nothing to draw: status 2.
set +e
"$root/tools/plot" "$out/nothing" 2>/dev/null
status=$?
set -e
[ "$status" -eq 2 ] || { echo "expected status 2, got $status"; exit 1; }
echo "1 passed, 0 failed"
