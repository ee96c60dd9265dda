#!/usr/bin/env bash
# The main job: a fleetmap-server and two fleetmap-agents on two real SLAM maps, over DDS on
# loopback. Shows the robots joining, the bytes the server receives, one robot dying (killed,
# noticed by liveliness) and one leaving on purpose, then the server's summary. Exits by itself.
set -euo pipefail

build_dir=${1:-build}
repo=$(cd "$(dirname "$0")/.." && pwd)
maps=${FLEETMAP_MAPS_DIR:-$repo/../shared/data/maps}
if [ ! -f "$maps/intel_lab.yaml" ] || [ ! -f "$maps/aces3_austin.yaml" ]; then
  maps=$repo/tests/data/maps
  first=$maps/trinary_4x3.yaml
  second=$maps/negate_4x3.yaml
  echo "run-demo: ../shared/data/maps not found; using the tiny fixtures in tests/data/maps"
else
  first=$maps/intel_lab.yaml
  second=$maps/aces3_austin.yaml
fi

server=$build_dir/server/fleetmap-server
agent=$build_dir/robot_agent/fleetmap-agent
for binary in "$server" "$agent"; do
  [ -x "$binary" ] || { echo "run-demo: $binary is missing: run 'make run'" >&2; exit 1; }
done

# A domain of its own, and loopback only: the demo sends nothing off this machine.
export FLEETMAP_DOMAIN=${FLEETMAP_DOMAIN:-$((100 + RANDOM % 100))}
export FLEETMAP_LOCALHOST_ONLY=1

pids=()
cleanup() { for pid in "${pids[@]}"; do kill -9 "$pid" 2>/dev/null || true; done; }
trap cleanup EXIT

echo "== fleetmap demo on DDS domain $FLEETMAP_DOMAIN: a server, robot alpha ($(basename "$first")), robot beta ($(basename "$second"))"
# Process substitution keeps $! the pid of the fleetmap process itself, not of sed.
"$server" --duration 10 > >(sed -u 's/^/[server] /') 2>&1 &
server_pid=$!
sleep 1
"$agent" --robot-id alpha --map "$first" --duration 7 > >(sed -u 's/^/[alpha]  /') 2>&1 &
pids+=($!)
"$agent" --robot-id beta --map "$second" --fleet-from-map 40 0 0 > >(sed -u 's/^/[beta]   /') 2>&1 &
beta_pid=$!
pids+=($beta_pid)
sleep 4
echo "== $(date +%T.%3N) killing robot beta (kill -9): the server should notice within about 2 s"
kill -9 "$beta_pid"
{ wait "$beta_pid"; } 2>/dev/null || true  # reap it quietly: the server reports the death
wait "$server_pid"
wait || true
sleep 0.2  # let sed flush the last lines
echo "== demo done"
