#!/usr/bin/env bash
# Drives the real contour window under Xvfb with xdotool — a drag of a
# point, a key (c: conic sweep), a save (s) — and checks it against the
# scripted run of the same edits: the window's screen equals
# `contour --script EDITS --screenshot` pixel for pixel, and the deck the
# window saved equals `contour --script EDITS -o NEW.deck` byte for byte.
# Needs xvfb-run (apt: xvfb), xdotool, xwd (x11-apps) and netpbm; when they
# are missing it skips, unless CI is set, when it fails.
set -euo pipefail
cd "$(dirname "$0")/.."
name=contour_xvfb

# shellcheck source=.ci/needs.sh
source .ci/needs.sh
needs "$name" "xvfb xdotool x11-apps netpbm" xvfb-run xdotool xwd xwdtopnm pngtopnm ppmtoppm cmp

cargo build --quiet --bin contour
bin="$(pwd)/${CARGO_TARGET_DIR:-target}/debug/contour"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

# The deck: Fig. 5.6's star at one ray a pixel (a quick preview). The
# window edits window/star.deck, the script script/star.deck: the same
# name, so the screens (which show it) can be equal.
mkdir -p "$tmp/window" "$tmp/script"
sed 's/mask 2/mask 1/' legacy_pascal/decks/fig5_6.deck >"$tmp/window/star.deck"
cp "$tmp/window/star.deck" "$tmp/script/star.deck"

# Point 3 on the screen, and the scale: a drag of 50 pixels right and 25
# up moves it by (50/S, 25/S).
"$bin" "$tmp/script/star.deck" star --list >"$tmp/list"
scale=$(sed -n '1s/.*(\([0-9.e+]*\) pixels a unit).*/\1/p' "$tmp/list")
read -r x y < <(awk -F'\t' '$1 == 3 { print $4, $5 }' "$tmp/list")
du=$(awk -v s="$scale" 'BEGIN { printf "%.10g", 50 / s }')
dv=$(awk -v s="$scale" 'BEGIN { printf "%.10g", 25 / s }')
printf 'move 3 %s %s\nsweep conic\n' "$du" "$dv" >"$tmp/edits"
(cd "$tmp/script" && "$bin" star.deck star --script ../edits --screenshot ../expected.png -o ../expected.deck)
pngtopnm "$tmp/expected.png" | ppmtoppm >"$tmp/expected.ppm"

# Inside the X server: open the window, drag, press c, grab the screen
# until it shows the finer preview (or 60 s pass), press s, then q.
status=0
xvfb-run -a -s "-screen 0 1024x864x24" bash -c '
    bin=$1 tmp=$2 x=$3 y=$4
    source "$5"
    cd "$tmp/window"
    "$bin" star.deck star 2>"$tmp/contour.err" &
    pid=$!
    wid=
    for _ in $(seq 100); do
        wid=$(xdotool search --name "^contour " 2>/dev/null | head -1) && [[ -n $wid ]] && break
        kill -0 "$pid" 2>/dev/null || exit 3
        sleep 0.2
    done
    [[ -n $wid ]] || exit 4
    sleep 1
    # Each step waits for a frame of the window (it reads the mouse 60
    # times a second).
    xdotool mousemove --window "$wid" "$x" "$y"; sleep 0.3
    xdotool mousedown 1; sleep 0.3
    xdotool mousemove --window "$wid" $((x + 10)) $((y - 5)); sleep 0.3
    xdotool mousemove --window "$wid" $((x + 50)) $((y - 25)); sleep 0.3
    xdotool mouseup 1; sleep 0.3
    xdotool key c
    deadline=$((SECONDS + 60))
    result=1
    while ((SECONDS < deadline)); do
        if screen_matches "$tmp"; then
            result=0
            break
        fi
        sleep 0.5
    done
    xdotool key s; sleep 1
    xdotool key q
    for _ in $(seq 50); do kill -0 "$pid" 2>/dev/null || break; sleep 0.1; done
    if kill -0 "$pid" 2>/dev/null; then
        kill "$pid"
        result=5
    fi
    wait "$pid" 2>/dev/null || result=6
    exit "$result"
' _ "$bin" "$tmp" "$x" "$y" "$(pwd)/.ci/needs.sh" || status=$?

case $status in
0) ;;
3) echo "$name: FAIL: contour exited before its window opened: $(tr '\n' ' ' <"$tmp/contour.err")"; exit 1 ;;
4) echo "$name: FAIL: no contour window appeared"; exit 1 ;;
5) echo "$name: FAIL: q did not close the window after the save"; exit 1 ;;
6) echo "$name: FAIL: contour exited with an error: $(tr '\n' ' ' <"$tmp/contour.err")"; exit 1 ;;
*) screen_differs "$name" "$tmp" "$status" "the window's screen differs from the scripted run's" ;;
esac
if ! cmp -s "$tmp/window/star.deck" "$tmp/expected.deck"; then
    echo "$name: FAIL: the deck the window saved differs from the scripted run's:"
    diff "$tmp/window/star.deck" "$tmp/expected.deck" || true
    exit 1
fi
echo "$name: PASS: a drag, c and s in the contour window under Xvfb equal 'move 3 $du $dv', 'sweep conic' and -o of the scripted run (screen and deck)"
