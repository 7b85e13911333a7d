#!/usr/bin/env bash
# `penumbra tune` sharded over a real Slurm cluster equals one process: starts a single-node
# cluster (scripts/slurm/local-cluster), submits two scenes x three techniques as an array of
# three shards and the merge as a job that depends on it (scripts/slurm/submit-tune), runs the
# same tune without --shard, and holds the two outputs equal: the best settings byte for byte,
# the rest but for measured times (tune_outputs_equal.py).
# Usage: tune_slurm_test.sh PENUMBRA OUT_DIR. Needs root (slurmd starts the jobs); skips (77)
# without root only outside CI: with CI=true it fails instead.
set -euo pipefail
penumbra="$1"
out="$2"
repo=$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)

if [ "$(id -u)" -ne 0 ]; then
  if [ "${CI:-}" = "true" ]; then
    echo "CI=true but not root: the local Slurm cluster needs root (slurmd starts the jobs)"
    exit 1
  fi
  echo "not root: skipping the Slurm cluster test"
  exit 77
fi

rm -rf "$out"
mkdir -p "$out"
# Two small scenes, three techniques: six units over three shards, two per shard.
# shellcheck disable=SC2054  # hard,vsm,esm is one argument
tune_args=(--scene backyard --scene planar --technique hard,vsm,esm --evaluations 4
           --width 160 --height 90 --shadow-size 256 --frames 2 --supersample 1 --quiet)

start=$SECONDS
# The cluster's own time limit, inside CTest's, so that a stuck job still gets the cluster torn
# down (local-cluster cancels the jobs and stops the daemons on TERM). Standard input is not a
# terminal even when run by hand: local-cluster would give the command the foreground and defer
# the TERM until it ends.
timeout --signal=TERM 150 "$repo/scripts/slurm/local-cluster" run -- \
  "$repo/scripts/slurm/submit-tune" --shards 3 --out "$out/cluster" --penumbra "$penumbra" \
  --wait -- "${tune_args[@]}" < /dev/null
echo "cluster: shards and merge in $((SECONDS - start)) s"
cat "$out"/cluster/logs/*.log

start=$SECONDS
"$penumbra" tune "${tune_args[@]}" --out "$out/local"
echo "local: one process in $((SECONDS - start)) s"

merged="$out/cluster/merged"
single="$out/local"
# Best settings, what users load: byte for byte, shown as a diff when not.
diff -r "$single/best" "$merged/best" || { echo "best settings differ"; exit 1; }
# Everything else but measured times (tune_outputs_equal.py says what may differ).
python3 "$repo/tests/cli/tune_outputs_equal.py" "$single" "$merged"
echo "the merged report equals the single run"
