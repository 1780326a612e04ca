#!/usr/bin/env bash
# Instructions per forward-dynamics call (forward_dynamics_instruction_count.cpp) on every shipped
# 6-axis robot: the generated ForwardDynamics and KDL's ChainFdSolver_RNE, counted by callgrind on
# measured() alone with the state cycling (kernel loop_<robot>) subtracted, and KDL / generated.
#
#   tests/benchmarks/forward_dynamics_instruction_counts.sh [program] [calls]
set -euo pipefail
program=${1:-build/bin/forward_dynamics_instruction_count}
calls=${2:-1000}
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
count() {
  valgrind --tool=callgrind --toggle-collect='modelgen::bench::measured*' \
    --callgrind-out-file="$out/$1.cg" "$program" "$1" "$calls" > /dev/null 2>&1
  awk '/^totals:/ {print $2}' "$out/$1.cg"
}
printf '%-18s %14s %14s %10s\n' robot generated KDL KDL/generated
for robot in $("$program" list | sed -n 's/^loop_//p'); do
  loop=$(count "loop_$robot")
  generated=$(( ($(count "generated_$robot") - loop) / calls ))
  kdl=$(( ($(count "kdl_$robot") - loop) / calls ))
  printf '%-18s %14d %14d %9.1fx\n' "$robot" "$generated" "$kdl" \
    "$(awk -v a="$kdl" -v b="$generated" 'BEGIN {print a / b}')"
done
