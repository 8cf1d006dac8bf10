# Sourced by the .ci/*_xvfb.sh checks and by their scripts inside Xvfb.
#
# `needs NAME "APT PACKAGES" TOOL…` returns when every TOOL is on PATH;
# otherwise it says which are missing and how to install them, and exits:
# 0 (SKIP) on a developer's machine, 1 (FAIL) when CI is set.
needs() {
    local name=$1 packages=$2 tool
    shift 2
    local missing=()
    for tool in "$@"; do
        command -v "$tool" >/dev/null 2>&1 || missing+=("$tool")
    done
    ((${#missing[@]})) || return 0
    local msg="missing ${missing[*]} (apt-get install -y $packages)"
    if [[ -n "${CI:-}" ]]; then
        echo "$name: FAIL: $msg"
        exit 1
    fi
    echo "$name: SKIP: $msg"
    exit 0
}

# `screen_differs NAME TMP STATUS WHAT`: says that the Xvfb screen never
# matched TMP/expected.ppm (WHAT "differs … in N bytes"), or that it could
# not be grabbed, and exits 1 (FAIL).
screen_differs() {
    local name=$1 tmp=$2 status=$3 what=$4 diff
    if [[ -s "$tmp/screen.ppm" ]]; then
        diff=$(cmp -l "$tmp/screen.ppm" "$tmp/expected.ppm" 2>/dev/null | wc -l || true)
        echo "$name: FAIL: $what in $diff bytes"
    else
        echo "$name: FAIL: could not grab the Xvfb screen (status $status)"
    fi
    exit 1
}

# `screen_matches TMP`: grabs the Xvfb screen into TMP/screen.ppm; true
# when it equals TMP/expected.ppm.
screen_matches() {
    xwd -root -silent >"$1/screen.xwd" 2>/dev/null &&
        xwdtopnm "$1/screen.xwd" 2>/dev/null | ppmtoppm >"$1/screen.ppm" 2>/dev/null &&
        cmp -s "$1/screen.ppm" "$1/expected.ppm"
}
