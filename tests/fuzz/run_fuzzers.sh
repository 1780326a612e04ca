#!/usr/bin/env bash
# Runs every fuzz target of tests/fuzz for a fixed number of inputs from its seed corpus
# (robots/ and tests/bad_inputs/), under the sanitizers it was built with; fails on a crash, a
# sanitizer report, an input error that is not a modelgen::Error, or an input taking over
# 10 s. Usage: tests/fuzz/run_fuzzers.sh BUILD_DIR [RUNS_PER_TARGET]. By default each target
# gets about half a minute on one core (CI's time budget; give more runs locally): the
# description loaders build the reference model for
# every accepted input (tens of inputs per second), the file readers run hundreds a second.
set -euo pipefail
build=$(cd "$1" && pwd)
runs=${2:-}
declare -A default_runs=([fuzz_mdh_yaml]=1500 [fuzz_urdf]=1000 [fuzz_data_csv]=10000
                         [fuzz_parameter_json]=10000 [fuzz_trajectory_yaml]=5000
                         [fuzz_controller_yaml]=5000 [fuzz_estimate_json]=5000
                         [fuzz_design_description]=300)
source_dir=$(cd "$(dirname "$0")/../.." && pwd)
work=$build/fuzz
rm -rf "$work"
mkdir -p "$work"
cd "$source_dir"

# seeds TARGET FILE...: the seed folder of TARGET.
seeds() {
  local target=$1
  shift
  mkdir -p "$work/$target/seeds" "$work/$target/corpus" "$work/$target/artifacts"
  local f
  for f in "$@"; do
    [ -f "$f" ] && cp "$f" "$work/$target/seeds/$(echo "$f" | tr / _)"
  done
  return 0
}
seeds fuzz_mdh_yaml robots/*.yaml tests/bad_inputs/yaml/*.yaml tests/bad_inputs/robots/*.yaml
seeds fuzz_urdf robots/urdf/*.urdf tests/bad_inputs/urdf/*.urdf
seeds fuzz_data_csv tests/bad_inputs/data/*.csv
head -40 robots/data/kr150/excitation.csv > "$work/fuzz_data_csv/seeds/kr150_excitation_head.csv"
seeds fuzz_parameter_json tests/bad_inputs/parameters/*.json tests/bad_inputs/robots/*.json \
  $(find robots/data -name '*.json' | sort)
seeds fuzz_trajectory_yaml tests/bad_inputs/trajectory/*.yaml \
  tests/bad_inputs/robots/two_axes_trajectory.yaml $(grep -rl '^period:' robots/data | sort)
seeds fuzz_estimate_json tests/bad_inputs/estimate/*.json
seeds fuzz_design_description tests/bad_inputs/design/*.yaml tests/bad_inputs/robots/*.yaml \
  $(grep -l 'limits:' robots/*.yaml | sort)
seeds fuzz_controller_yaml tests/bad_inputs/controller/*.yaml \
  $(find robots/data -name 'controller*.yaml' | sort)

export ASAN_OPTIONS=${ASAN_OPTIONS:-detect_leaks=1}
export UBSAN_OPTIONS=${UBSAN_OPTIONS:-print_stacktrace=1}
failed=0
for target in fuzz_mdh_yaml fuzz_urdf fuzz_data_csv fuzz_parameter_json fuzz_trajectory_yaml \
              fuzz_controller_yaml fuzz_estimate_json fuzz_design_description; do
  max_len=4096
  [ "$target" = fuzz_urdf ] && max_len=32768
  # A description near the 32-joint limit takes about 65 s of CPU to derive under the
  # sanitizers (found by this run from the 33-joint seed): a slow legal input, not a hang.
  # The design target derives every description it is given as well.
  timeout=10
  case $target in fuzz_mdh_yaml | fuzz_urdf | fuzz_design_description) timeout=180 ;; esac
  start=$(date +%s)
  if "$build/bin/$target" -runs="${runs:-${default_runs[$target]}}" -seed=1 -max_len="$max_len" -timeout="$timeout" \
      -rss_limit_mb=2560 -print_final_stats=1 -artifact_prefix="$work/$target/artifacts/" \
      "$work/$target/corpus" "$work/$target/seeds" > "$work/$target/log" 2>&1; then
    status=passed
  else
    status=FAILED
    failed=1
  fi
  executed=$(sed -n 's/^stat::number_of_executed_units: *//p' "$work/$target/log")
  echo "fuzz: $target: ${executed:-?} inputs in $(( $(date +%s) - start )) s: $status"
  if [ "$status" = FAILED ]; then
    grep -E "ERROR|runtime error|fuzz: not an input error|Test unit written|SUMMARY" \
      "$work/$target/log" | head -20
    echo "fuzz: full log $work/$target/log; reproduce: $build/bin/$target $work/$target/artifacts/<file>"
  fi
done
exit $failed
