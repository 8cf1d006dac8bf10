# farm/programs.sh: the programs the farm scripts run, sourced by
# farm/parallel.sh and farm/slurm/submit.sh after farm/args.sh. raytrace
# and tools from PATH when both are there (`cargo install --path .` and
# `cargo install --path tools`); else the checkout's release build,
# target/release/ (or $CARGO_TARGET_DIR/release), built once (`cargo build
# --release`) when one is missing. Sets raytrace and tools to the commands
# to run, and says on stderr which it uses.
checkout=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
if command -v raytrace >/dev/null 2>&1 && command -v tools >/dev/null 2>&1; then
  raytrace=raytrace tools=tools
  echo "$0: using raytrace and tools from PATH ($(command -v raytrace))" >&2
else
  target=${CARGO_TARGET_DIR:-target}
  case $target in /*) ;; *) target=$checkout/$target ;; esac
  raytrace=$target/release/raytrace tools=$target/release/tools
  if [ ! -x "$raytrace" ] || [ ! -x "$tools" ]; then
    echo "$0: raytrace and tools are not on PATH: building the checkout's once (cargo build --release)" >&2
    (cd "$checkout" && cargo build --release --quiet -p raytrace -p tools --bin raytrace --bin tools)
  fi
  echo "$0: using the checkout's $raytrace and $tools" >&2
fi
