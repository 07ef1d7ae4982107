#!/usr/bin/env bash
# tools/plot on a real fit: three PNGs per segment, each a real image.
set -euo pipefail
bin="$1"
root="$2"
out="$(mktemp -d)"
trap 'rm -rf "$out"' EXIT
"$bin" fit "$root/configs/report/table6_sigma0.02.yaml" --out_dir="$out" >/dev/null 2>&1
"$root/tools/plot" "$out" >/dev/null
for kind in motion residuals psi_theta; do
  f="$out/table6-sigma0.02_$kind.png"
  [ -s "$f" ] || { echo "missing $f"; exit 1; }
  head -c 8 "$f" | od -An -c | grep -q "P   N   G" || { echo "$f is not a PNG"; exit 1; }
  [ "$(stat -c %s "$f")" -gt 20000 ] || { echo "$f is suspiciously small"; exit 1; }
done
# A diagnose directory: every step is drawn.
"$bin" diagnose "$root/configs/report/table6_sigma0.02.yaml" --out_dir="$out/diagnose" >/dev/null 2>&1
"$root/tools/plot" "$out/diagnose" >/dev/null
[ -s "$out/diagnose/step0/table6-sigma0.02_residuals.png" ] || { echo "no diagnose plots"; exit 1; }
# A missing fit directory is a clear error, status 2.
set +e
"$root/tools/plot" "$out/nothing" 2>/dev/null
status=$?
set -e
[ "$status" -eq 2 ] || { echo "expected status 2, got $status"; exit 1; }
echo "1 passed, 0 failed"
