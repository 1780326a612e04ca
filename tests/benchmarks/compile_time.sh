#!/usr/bin/env bash
# Compile time of generated code at -O2 (issue 15): the whole TX-40 model with -j2 (one file per
# function, as modelgen_generate() builds it), TX-40 inverse_dynamics alone, and the base
# regressor of a 16-joint chain (SymPyBotics needs 6.6 s for its single regressor file of such
# a chain, the anchor of the issue). Wall times, best of three.
# Usage: tests/benchmarks/compile_time.sh [BUILD_DIR]   (BUILD_DIR holds bin/modelgen; default build)
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
build=${1:-$root/build}
modelgen=$build/bin/modelgen
cxx=${CXX:-g++}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

best_of_three() {  # prints the best wall time in seconds of the command
  local best=""
  for _ in 1 2 3; do
    local start end
    start=$(date +%s.%N)
    "$@" >/dev/null
    end=$(date +%s.%N)
    best=$(echo "$start $end ${best:-1e9}" | awk '{t = $2 - $1; print (t < $3 ? t : $3)}')
  done
  printf '%.2f' "$best"
}
compile_all() {  # compiles every .cpp of a folder, two at a time, largest first (as make -j2
  local dir=$1  # would schedule them at best)
  ls -S "$dir"/*.cpp | xargs -P 2 -I{} "$cxx" -std=c++11 -O2 -c {} -o {}.o
}
compile_one_file() {  # all functions of a folder concatenated into one file, as before issue 15
  local dir=$1
  { cat "$dir"/*.hpp | grep -v '^#include'; cat "$dir"/*.cpp | grep -v '^#include "'; } \
    >"$work/single.cpp"
  "$cxx" -std=c++11 -O2 -c "$work/single.cpp" -o "$work/single.o"
}

"$modelgen" "$root/robots/tx40.yaml" -o "$work/tx40" 2>/dev/null
files=$(find "$work/tx40" -name '*.cpp' | wc -l)
echo "tx40, whole model ($files files, -j2):       $(best_of_three compile_all "$work/tx40") s"
echo "tx40, whole model as one file:             $(best_of_three compile_one_file "$work/tx40") s"
echo "tx40, inverse_dynamics alone:              $(best_of_three "$cxx" -std=c++11 -O2 -c \
  "$work/tx40/tx40_inverse_dynamics.cpp" -o "$work/id.o") s"

# A 16-joint chain of alternately parallel and perpendicular revolute axes.
{
  echo "name: chain16"
  echo "joints:"
  for j in $(seq 1 16); do
    if [ $((j % 2)) -eq 0 ]; then alpha="pi/2"; else alpha=0; fi
    if [ "$j" -eq 1 ]; then alpha=0; fi
    echo "  - {name: J$j, type: revolute, alpha: $alpha, d: 0.1, theta: 0, r: 0.05}"
  done
} >"$work/chain16.yaml"
"$modelgen" "$work/chain16.yaml" -o "$work/chain16" --functions idim_regressor --scalar double \
  2>/dev/null
echo "chain16, idim_regressor (SymPyBotics 6.6 s): $(best_of_three "$cxx" -std=c++11 -O2 -c \
  "$work/chain16/chain16_idim_regressor.cpp" -o "$work/reg.o") s"
