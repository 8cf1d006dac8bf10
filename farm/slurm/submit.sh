#!/bin/bash
# farm/slurm/submit.sh film DECK A-B | still DECK N
#
# Submits a job array and the job that joins it:
#   film:  film.sbatch, a task a frame A..B; the join writes OUT/<deck name>.png,
#          the frames' animated PNG (tools join, at RATE frames a second, 12);
#   still: still.sbatch, a task a band of N; the join writes OUT/<deck name>.ras,
#          the whole image (tools join --tiles).
# The join starts once every task has succeeded (--dependency=afterok) and is
# cancelled if one fails (--kill-on-invalid-dep=yes). Prints the join's job id.
# OUT (default raster/farm-out) holds the frames or bands, the joined file and the
# jobs' logs (OUT/logs); FLAGS adds raytrace flags to every task; TASKS, if
# set, is the most tasks that run at once (--array=…%TASKS). Run it from the
# checkout (the tasks cd to the folder it was run from). raytrace and tools
# are PATH's, which must then be on every node's PATH, or else the
# checkout's release build, built once if missing (farm/programs.sh), which
# the nodes run from the shared folder.
set -euo pipefail
. "$(dirname "$0")/../args.sh"
. "$(dirname "$0")/../programs.sh"
mkdir -p "$out/logs"
logs=(--output="$out/logs/%x_%A_%a.out")
limit=${TASKS:+%$TASKS}
case $kind in
  film)
    tasks=$(sbatch --parsable --array="$count$limit" "${logs[@]}" --export="ALL,DECK=$deck,OUT=$out,RAYTRACE=$raytrace" farm/slurm/film.sbatch)
    printf -v join '%q join %q.[0-9]*.ras -o %q --rate %q' "$tools" "$out/$stem" "$out/$stem.png" "${RATE:-12}"
    ;;
  still)
    tasks=$(sbatch --parsable --array="1-$count$limit" "${logs[@]}" --export="ALL,DECK=$deck,OUT=$out,TILES=$count,RAYTRACE=$raytrace" farm/slurm/still.sbatch)
    join="$(printf '%q ' "$tools" join --tiles $(seq -f "$out/$stem.%g-of-$count.ras" "$count") -o "$out/$stem.ras")"
    ;;
esac
sbatch --parsable --job-name="join-$stem" --dependency="afterok:$tasks" --kill-on-invalid-dep=yes \
    --output="$out/logs/%x_%j.out" --wrap "$join"
