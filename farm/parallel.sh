#!/bin/bash
# farm/parallel.sh film DECK A-B | still DECK N
#
# The tasks of farm/slurm/submit.sh with GNU parallel, then the join:
#   film:  a job a frame A..B, then OUT/<deck name>.png (tools join, RATE fps, 12);
#   still: a job a band of N, then OUT/<deck name>.ras (tools join --tiles).
# On this host, JOBS jobs at once (default one a core). With HOSTS, parallel's
# --sshlogin list (e.g. 2/:,4/render1,4/render2: JOBS/HOST, ':' this host),
# the jobs run over ssh on those hosts in this folder, which they must share
# at the same path. raytrace and tools are PATH's, or else the checkout's
# release build, built once if missing (farm/programs.sh); over ssh, PATH's
# must be on each host's PATH, the checkout's in the shared folder. OUT
# (default raster/farm-out) holds the parts and the joined file; FLAGS adds
# raytrace flags to every job. A job that fails stops the rest (--halt
# now,fail=1); run again, the parts already written whole are kept (--resume).
set -euo pipefail
. "$(dirname "$0")/args.sh"
. "$(dirname "$0")/programs.sh"
where=(--jobs "${JOBS:-100%}")
if [ -n "${HOSTS:-}" ]; then
  where=(--sshlogin "$HOSTS" --workdir "$PWD")
fi
# FLAGS is split into words, as the sbatch scripts split it.
read -r -a flags <<<"${FLAGS:-}"
case $kind in
  film)
    seq "${count%-*}" "${count#*-}" |
      parallel --will-cite "${where[@]}" --halt now,fail=1 \
        "$raytrace" "$deck" -o "$out/$stem.ras" --frames {} --threads 1 --resume --quiet "${flags[@]}"
    "$tools" join "$out/$stem".[0-9]*.ras -o "$out/$stem.png" --rate "${RATE:-12}"
    ;;
  still)
    seq "$count" |
      parallel --will-cite "${where[@]}" --halt now,fail=1 \
        "$raytrace" "$deck" --tile {}/"$count" -o "$out/$stem.{}-of-$count.ras" --threads 1 --resume --quiet "${flags[@]}"
    mapfile -t parts < <(seq -f "$out/$stem.%g-of-$count.ras" "$count")
    "$tools" join --tiles "${parts[@]}" -o "$out/$stem.ras"
    ;;
esac
