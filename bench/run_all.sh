#!/usr/bin/env bash
# Every figure of docs/results.md, in one run: bash bench/run_all.sh [BUILD_DIR] [OUT_DIR]
# Each command's stdout goes to OUT_DIR/<name>.txt (and its JSON/CSV beside it); the commands are
# the ones docs/results.md names. About 50 minutes on the 2-core reference machine. The lossy
# network run needs root (a network namespace and an nftables rule) and is skipped otherwise.
set -euo pipefail

build=${1:-build}
out=${2:-out/results}
maps=${FLEETMAP_MAPS:-../shared/data/maps}
fleetmap="$build/cli/fleetmap"
mkdir -p "$out"

run() {
  local name=$1
  shift
  echo "== $name: $*" >&2
  local start=$SECONDS
  "$@" > "$out/$name.txt"
  echo "   $name done in $((SECONDS - start)) s" >&2
}

[[ -d $maps ]] || maps=tests/data/maps/real  # a lone clone: the three maps it carries

run vectorize "$fleetmap" bench vectorize --maps "$maps" --runs 7 \
  --json "$out/vectorize.json" --csv "$out/vectorize.csv"
if [[ -x $build/bench/kernels/vectorize_benchmark ]]; then
  run kernels "$build/bench/kernels/vectorize_benchmark" --benchmark_min_time=0.2
  run tile_codec "$build/bench/kernels/tile_codec_benchmark" --benchmark_min_time=0.2
fi
run paper "$fleetmap" bench paper --out "$out/paper" --seed 1 --no-progress
run fleet "$fleetmap" bench fleet --robots 1 4 16 --terrain office --size 80 --duration 45 \
  --rate 10 --json "$out/fleet.json"
run demo "$fleetmap" sim --robots 4 --terrain office --size 40 --duration 40 --out "$out/demo"
run secure "$fleetmap" sim --secure --robots 4 --terrain office --size 40 --duration 40 \
  --out "$out/secure"
run hostile "$fleetmap" bench fleet --robots 1 4 --terrain office --size 40 --duration 30 \
  --hostile --json "$out/hostile.json"
if [[ $(id -u) -eq 0 ]]; then
  run loss "$fleetmap" bench loss --loss 0 5 20 40 --robots 4 --terrain office --size 40 \
    --duration 40 --rate 10 --json "$out/loss.json" --csv "$out/loss.csv"
else
  echo "== loss: skipped (needs root for the network namespace)" >&2
fi
for seed in 1 2 3; do
  run "objects_lab$seed" "$fleetmap" bench objects --out "$out/objects_lab$seed" --starts 20 \
    --seed "$seed"
done
run objects_office1 "$fleetmap" bench objects --terrain office --size 40 \
  --out "$out/objects_office1" --starts 20 --seed 1
run objects_real "$fleetmap" bench objects --no-sim --maps "$maps" --out "$out/objects_real" \
  --seed 1
run extrapolation_1 "$fleetmap" bench extrapolation --out "$out/extrapolation_1" --scenes 100 \
  --seed 1 --no-progress
run extrapolation_1001 "$fleetmap" bench extrapolation --out "$out/extrapolation_1001" \
  --scenes 100 --seed 1001 --no-progress
# Issue 36: closed doors on plans with never-entered rooms and on the real maps (strict scoring).
for seed in 1 1001; do
  run "extrapolation_plans$seed" "$fleetmap" bench extrapolation --out "$out/extrapolation_plans$seed" \
    --plans 100 --scenes 0 --seed "$seed" --no-progress
done
run extrapolation_real "$fleetmap" bench extrapolation --out "$out/extrapolation_real" \
  --real-maps "$maps" --scenes 0 --no-progress
for events in 2 5; do
  run "objects_small$events" "$fleetmap" bench objects --small-pieces 20 --seed 1 \
    --speck-events "$events" --out "$out/objects_small$events"
done
run objects_contrast "$fleetmap" bench objects --contrast --data-sets 3 --starts 20 \
  --out "$out/objects_contrast"
run register "$fleetmap" bench register --maps "$maps" --pairs-per-overlap 12 --seed 1 \
  --json "$out/register.json" --csv "$out/register.csv"
run route_graph "$fleetmap" bench route-graph --maps "$maps" --runs 5 \
  --json "$out/route_graph.json" --csv "$out/route_graph.csv"
run quarantine "$fleetmap" bench quarantine --runs 3 --out "$out/quarantine"
run failover "$fleetmap" bench failover --robots 8 --runs 10 --out "$out/failover"
run capacity "$fleetmap" bench capacity --robots 8 16 32 64 128 256 --out "$out/capacity"
echo "all figures in $out" >&2
