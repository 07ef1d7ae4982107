#!/usr/bin/env bash
# The sanitized build's two builds of the Jet units (CMakeLists.txt): the
# tests of the Jet code (FIT3DOF_JET_CHECKED_TESTS) must carry the units
# built with ASan, every other binary the library's, built without it.
# Looks for ASan's report calls in one function of each kind of Jet unit:
# the cost function's Jet lanes, the sensitivities, the motion filter.
#
#   jet_checked_test.sh checked:BINARY... unchecked:BINARY...
set -euo pipefail

functions=(
  'fit3dof::SegmentCostFunction::EvaluateLanes<4>('
  'fit3dof::MotionModel::EvaluateWithSensitivities('
  'fit3dof::MotionModel::EvaluateFiltered<ceres::Jet<double, 4> >('
)

# Each defined symbol of binary $1: its mangled name, a tab, its demangled.
symbols() {
  paste -d '\t' <(nm --defined-only "$1" | awk '{print $3}') \
    <(nm --defined-only -C "$1" | cut -d' ' -f3-)
}

# The mangled name of the first symbol in table $1 whose demangled name
# contains $2.
mangled() {
  awk -F '\t' -v want="$2" '!found && index($2, want) { print $1; found = 1 }' \
    <<<"$1"
}

failures=0
for arg in "$@"; do
  expect="${arg%%:*}"
  binary="${arg#*:}"
  table="$(symbols "$binary")"
  for f in "${functions[@]}"; do
    symbol="$(mangled "$table" "$f")"
    if [ -z "$symbol" ]; then
      echo "FAIL $(basename "$binary"): no function $f"
      failures=$((failures + 1))
      continue
    fi
    reports="$(objdump -d --no-show-raw-insn --disassemble="$symbol" \
      "$binary" | grep -c '__asan_report' || true)"
    if { [ "$expect" = checked ] && [ "$reports" -eq 0 ]; } ||
      { [ "$expect" = unchecked ] && [ "$reports" -ne 0 ]; }; then
      echo "FAIL $(basename "$binary"): $f has $reports ASan reports," \
        "expected $expect"
      failures=$((failures + 1))
    else
      echo "ok   $(basename "$binary"): $f $expect ($reports ASan reports)"
    fi
  done
done
exit $((failures > 0))
