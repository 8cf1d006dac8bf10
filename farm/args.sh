# farm/args.sh: the arguments farm/slurm/submit.sh and farm/parallel.sh
# share, `film DECK A-B` or `still DECK N`, sourced by both. Sets kind,
# deck, count, out (OUT, default raster/farm-out) and stem (the deck's name
# without .deck), and makes the folder out; a wrong line ends the script
# with status 2.
if [ $# != 3 ] || { [ "$1" != film ] && [ "$1" != still ]; }; then
  echo "usage: $0 film DECK A-B | still DECK N" >&2
  exit 2
fi
kind=$1 deck=$2 count=$3
out=${OUT:-raster/farm-out}
stem=${deck##*/}
stem=${stem%.deck}
mkdir -p "$out"
