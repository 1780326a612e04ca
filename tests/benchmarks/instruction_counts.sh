#!/usr/bin/env bash
# Instructions per call of each kernel of instruction_count.cpp (TX-40: generated functions, the
# numeric reference, KDL), counted by valgrind's callgrind on measured() alone, the cycling over
# states (kernel `loop`) subtracted, with the ratios the issues quote. Deterministic: the same
# binary gives the same counts on any machine of the same architecture.
#
#   tests/benchmarks/instruction_counts.sh [build/bin/instruction_count] [calls]
set -euo pipefail
program=${1:-build/bin/instruction_count}
calls=${2:-2000}
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
count() {
  valgrind --tool=callgrind --toggle-collect='modelgen::bench::measured*' \
    --callgrind-out-file="$out/$1.cg" "$program" "$1" "$calls" > /dev/null 2>&1
  awk '/^totals:/ {print $2}' "$out/$1.cg"
}
loop=$(count loop)
declare -A per_call
printf '%-40s %12s\n' kernel instructions/call
for kernel in $("$program" list); do
  [ "$kernel" = loop ] && continue
  total=$(count "$kernel")
  per_call[$kernel]=$(( (total - loop) / calls ))
  printf '%-40s %12d\n' "$kernel" "${per_call[$kernel]}"
done
ratio() { awk -v a="$1" -v b="$2" 'BEGIN {printf "%.1f", a / b}'; }
echo
echo "KDL RNE / generated inverse dynamics, sin and cos given: $(ratio "${per_call[kdl_rne]}" "${per_call[generated_inverse_dynamics_sincos]}")x"
echo "KDL RNE / generated inverse dynamics:                   $(ratio "${per_call[kdl_rne]}" "${per_call[generated_inverse_dynamics]}")x"
echo "reference / generated standard regressor (sin, cos given): $(ratio "${per_call[reference_standard_regressor]}" "${per_call[generated_standard_regressor_sincos]}")x"
echo "reference / generated inverse dynamics (standard):      $(ratio "${per_call[reference_inverse_dynamics]}" "${per_call[generated_inverse_dynamics_standard]}")x"
echo "reference / generated drive-model Jacobian per sample:  $(ratio "${per_call[reference_drive_jacobian]}" "${per_call[generated_drive_jacobian]}")x"
