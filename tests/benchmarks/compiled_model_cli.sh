#!/usr/bin/env bash
# Wall time of a closed-loop campaign on a robot modelid does not ship (issue 28): the PUMA 560
# of tests/model/loadable/puma560.yaml with the plausible inertials of puma560/true.json under
# the PID of puma560/controller.yaml. Steps: design (5 harmonics, 6 axes), simulate 30 s at
# 1 kHz under the controller (identification and validation records), fit IV and DIDIM on the
# 30 s record, validate. First with an empty cache (the first step pays the compilation), then
# IV again with a fresh cache (first run including generation and compilation) and, with
# --numeric, every step through the numeric reference (--no-compile; DIDIM alone takes many
# minutes that way). Prints one line per step: seconds compiled, and numeric with --numeric.
# Usage: tests/benchmarks/compiled_model_cli.sh [BUILD_DIR] [--numeric]
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
build=${1:-$root/build}
numeric=${2:-}
modelid=$build/bin/modelid
robot=$root/tests/model/loadable/puma560.yaml
data=$root/tests/benchmarks/puma560
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

seconds() {  # runs the command, prints its wall time in seconds
  local start end
  start=$(date +%s.%N)
  "$@" >"$work/last.out" 2>"$work/last.err" || { cat "$work/last.err" >&2; return 1; }
  end=$(date +%s.%N)
  echo "$start $end" | awk '{printf "%.2f", $2 - $1}'
}
campaign() {  # the steps, each printed as "step seconds"; $1: extra options of every run
  local extra=$1
  local sim="simulate --robot $robot --params $data/true.json --controller $data/controller.yaml
             --noise-tau 0.2 --encoder-resolution 1.5e-6 --periods 3"
  echo "design $(seconds "$modelid" design --robot "$robot" --period 10 --harmonics 5 --seed 1 \
    -o "$work/design.yaml" $extra)"
  echo "simulate $(seconds "$modelid" $sim --trajectory "$work/design.yaml" --seed 1 \
    -o "$work/id.csv" $extra)"
  "$modelid" design --robot "$robot" --period 10 --harmonics 5 --seed 2 \
    -o "$work/validation.yaml" $extra >/dev/null 2>&1
  "$modelid" $sim --trajectory "$work/validation.yaml" --seed 2 -o "$work/val.csv" $extra \
    >/dev/null 2>&1
  for method in iv didim; do
    echo "fit_$method $(seconds "$modelid" fit --robot "$robot" --data "$work/id.csv" \
      --method $method --controller "$data/controller.yaml" -o "$work/$method.json" $extra)"
  done
  echo "validate $(seconds "$modelid" validate --robot "$robot" --params "$work/iv.json" \
    --controller "$data/controller.yaml" --data "$work/val.csv" $extra)"
}

export MODELGEN_CACHE_DIR=$work/cache
echo "compiled model (the design pays the first-use compilation; $(nproc) cores):"
campaign "" | awk '{printf "  %-10s %8s s\n", $1, $2}'
rm -rf "$work/cache"
echo "  fit_iv, first run with an empty cache (generation and compilation included):" \
  "$(seconds "$modelid" fit --robot "$robot" --data "$work/id.csv" --method iv \
    --controller "$data/controller.yaml" -o "$work/iv_first.json") s"
if [ "$numeric" = "--numeric" ]; then
  echo "numeric reference (--no-compile):"
  campaign "--no-compile" | awk '{printf "  %-10s %8s s\n", $1, $2}'
fi
