#!/usr/bin/env bash
# Shows tests/data/psout_check.ras in a real psout window under Xvfb, grabs
# the screen with xwd and checks it equals `psout --screenshot` pixel for
# pixel. Needs xvfb-run (apt: xvfb), xwd (x11-apps) and netpbm; when they are
# missing it skips, unless CI is set, when it fails.
set -euo pipefail
cd "$(dirname "$0")/.."
name=psout_xvfb
ras=tests/data/psout_check.ras

# shellcheck source=.ci/needs.sh
source .ci/needs.sh
needs "$name" "xvfb x11-apps netpbm" xvfb-run xwd xwdtopnm pngtopnm ppmtoppm cmp

cargo build --quiet --bin psout
bin="${CARGO_TARGET_DIR:-target}/debug/psout"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

"$bin" --screenshot "$tmp/expected.png" "$ras"
pngtopnm "$tmp/expected.png" | ppmtoppm >"$tmp/expected.ppm"

# Inside the X server: start the window, grab the root window until it
# shows the raster (or 30 s pass), then close psout.
status=0
xvfb-run -a -s "-screen 0 1024x864x24" bash -c '
    bin=$1 ras=$2 tmp=$3
    source "$4"
    "$bin" "$ras" 2>"$tmp/psout.err" &
    pid=$!
    deadline=$((SECONDS + 30))
    result=1
    while ((SECONDS < deadline)); do
        if ! kill -0 "$pid" 2>/dev/null; then
            result=3
            break
        fi
        if screen_matches "$tmp"; then
            result=0
            break
        fi
        sleep 0.5
    done
    kill "$pid" 2>/dev/null || true
    wait "$pid" 2>/dev/null || true
    exit "$result"
' _ "$bin" "$ras" "$tmp" "$(pwd)/.ci/needs.sh" || status=$?

case $status in
0)
    echo "$name: PASS: the psout window under Xvfb equals psout --screenshot (1024×864, $ras)"
    ;;
3)
    echo "$name: FAIL: psout exited before its window showed the raster: $(tr '\n' ' ' <"$tmp/psout.err")"
    exit 1
    ;;
*) screen_differs "$name" "$tmp" "$status" "the grabbed screen differs from psout --screenshot ($ras)" ;;
esac
