#!/bin/bash
# farm/check.sh: the recipes of docs/farm.md, run as written, proven equal
# to one process. CI runs it (.ci/run); any machine may.
#
# 1. Renders, one process each, nec_commercial's frames 1..8 (and their
#    animated PNG) and fig5_8 at 512×512: the references.
# 2. Starts the one-node Slurm of farm/local-slurm.sh and submits, as
#    docs/farm.md does, the frames 1..8 as a job array and fig5_8 as a
#    4-band array, each joined by a job that waits for its array
#    (--dependency=afterok); stops the cluster.
# 3. Does the same with GNU parallel (farm/parallel.sh).
# 4. Compares every frame, the animated PNG and the whole still with the
#    references (cmp), and prints the line that says they are identical.
#
# Every daemon it starts is stopped when it ends, however it ends (a trap
# on EXIT). A machine that cannot run Slurm or has no GNU parallel (not
# root, packages missing) is said so; under CI (CI set) that fails, else
# the check is skipped. The work is in target/farm-check/.
set -euo pipefail
cd "$(dirname "$0")/.."
root=$PWD

say() { echo "farm/check.sh: $*" >&2; }

cannot=()
command -v parallel >/dev/null 2>&1 || cannot+=("GNU parallel is not installed (apt-get install parallel)")
for p in munged slurmctld slurmd sbatch; do
  command -v "$p" >/dev/null 2>&1 || [ -x "/usr/sbin/$p" ] ||
    cannot+=("$p is not installed (apt-get install slurmctld slurmd slurm-client munge)")
done
[ "$(id -u)" = 0 ] || cannot+=("not root: the one-node Slurm of farm/local-slurm.sh runs its daemons as root")
if [ ${#cannot[@]} -gt 0 ]; then
  printf 'farm/check.sh: cannot run here: %s\n' "${cannot[@]}" >&2
  if [ -n "${CI:-}" ]; then
    say "failed: CI must prove the farm recipes"
    exit 1
  fi
  say "skipped (outside CI)"
  exit 0
fi

# The binaries the recipes call, on PATH as on every node of a farm: the
# test profile's, which `cargo test --workspace` has just built.
cargo build --profile test -p raytrace -p tools --bins --quiet
export PATH=$root/target/debug:$PATH

work=$root/target/farm-check
rm -rf "$work"
# A folder for each way, with what a checkout gives the recipes.
for way in one slurm parallel; do
  mkdir -p "$work/$way"
  ln -s "$root/legacy_pascal" "$root/farm" "$work/$way/"
done

started=$SECONDS
cd "$work/one"
mkdir -p raster/farm-out
raytrace legacy_pascal/decks/nec_commercial.deck --frames 1..8 -o raster/farm-out/nec_commercial.ras \
  --apng raster/farm-out/nec_commercial.png --quiet
raytrace legacy_pascal/decks/fig5_8.deck --size 512x512 -o raster/farm-out/fig5_8.ras --quiet

# Slurm: the cluster is stopped on any exit from here on.
export FARM_SLURM_DIR=$work/slurm-cluster
export SLURM_CONF=$FARM_SLURM_DIR/slurm.conf
trap 'farm/local-slurm.sh stop' EXIT
trap 'exit 130' INT
trap 'exit 143' TERM
cd "$work/slurm"
farm/local-slurm.sh start

# Waits for Slurm jobs to end (at most 5 minutes); fails unless each COMPLETED.
wait_jobs() {
  local job state deadline=$((SECONDS + 300))
  for job in "$@"; do
    while :; do
      state=$(scontrol show job "$job" -o 2>/dev/null | sed -n 's/.*JobState=\([A-Z_]*\).*/\1/p')
      case $state in
        COMPLETED) break ;;
        PENDING | RUNNING | CONFIGURING | COMPLETING | '') ;;
        *)
          say "job $job ended $state; its logs:"
          tail -n 20 raster/farm-out/logs/* >&2 || true
          exit 1
          ;;
      esac
      if [ $SECONDS -gt $deadline ]; then
        say "job $job is still $state after 5 minutes"
        squeue >&2 || true
        exit 1
      fi
      sleep 0.5
    done
  done
}

film=$(farm/slurm/submit.sh film legacy_pascal/decks/nec_commercial.deck 1-8)
still=$(FLAGS="--size 512x512" farm/slurm/submit.sh still legacy_pascal/decks/fig5_8.deck 4)
wait_jobs "$film" "$still"
farm/local-slurm.sh stop
trap - EXIT

cd "$work/parallel"
farm/parallel.sh film legacy_pascal/decks/nec_commercial.deck 1-8 >/dev/null
FLAGS="--size 512x512" farm/parallel.sh still legacy_pascal/decks/fig5_8.deck 4 >/dev/null

# Everything the farms wrote equals one process's bytes.
cd "$work"
files=(nec_commercial.000{1..8}.ras nec_commercial.png fig5_8.ras)
for way in slurm parallel; do
  for f in "${files[@]}"; do
    if ! cmp "one/raster/farm-out/$f" "$way/raster/farm-out/$f"; then
      say "$way: $f differs from the one-process render"
      exit 1
    fi
  done
done
echo "farm/check.sh: Slurm (job arrays, joined after them) and GNU parallel: nec_commercial frames 1..8, their APNG and fig5_8 at 512×512 in 4 bands are identical to one process's renders ($((SECONDS - started)) s)"
