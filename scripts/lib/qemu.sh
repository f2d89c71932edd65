# What the QEMU scripts (qemu-run.sh, qemu-cycles.sh, qemu-serial.sh) share. Sourced, not run:
#
#   source "$(dirname "${BASH_SOURCE[0]}")/lib/qemu.sh" SCRIPT [SUFFIX]
#
# SCRIPT names the script in messages; SUFFIX (-selfcheck, -cycles) is the suffix of the image
# files it runs, which its arguments may carry too. Sets ROOT (the repository), FW
# (firmware-examples/), NODES, the defaults of the common options (BUILD, TIMEOUT, SELECTED) and
# the counters PASSED, FAILED, FAILURES and JSON (one JSON object per run, for write_runs).

SCRIPT=$1
SUFFIX=${2:-}
ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)
FW="$ROOT/firmware-examples"
# The serial nodes; each has a -selfcheck and a -cycles image.
NODES=(ant-node ant-node-fixed bee-node bee-node-fixed fly-node fly-node-fixed)
BUILD=0
TIMEOUT=60
SELECTED=()
PASSED=0
FAILED=0
FAILURES=()
JSON=()

# The comment block at the top of the script: its --help.
usage() {
    awk 'NR > 1 && /^set /{exit} NR > 1' "$0"
}

# parse_args "$@": each argument goes to the script's own script_arg if it defines one (which
# returns false for an argument that is not its own, and sets ARGS_USED to 2 when it takes a
# value), else to common_arg.
parse_args() {
    while [ $# -gt 0 ]; do
        ARGS_USED=1
        { declare -F script_arg >/dev/null && script_arg "$@"; } || common_arg "$@"
        shift "$ARGS_USED"
    done
}

# common_arg ARG [VALUE...]: the arguments every script takes: --build, --timeout S, -h/--help,
# --self-test where the script set SELFTEST, and a node (ant-node, ant-node-fixed, bee-node,
# bee-node-fixed, fly-node, fly-node-fixed, or one of them with SUFFIX), added to SELECTED.
# Exits 2 on any other argument.
common_arg() {
    case "$1" in
        --build) BUILD=1; return ;;
        --timeout) TIMEOUT=${2:?--timeout needs seconds}; ARGS_USED=2; return ;;
        -h|--help) usage; exit 0 ;;
        --self-test) if [ -n "${SELFTEST:-}" ]; then SELFTEST=1; return; fi ;;
    esac
    local node
    for node in "${NODES[@]}"; do
        if [ "$1" = "$node" ] || [ "$1" = "$node$SUFFIX" ]; then
            SELECTED+=("$node"); return
        fi
    done
    echo "$SCRIPT: unknown argument '$1' (try --help)" >&2; exit 2
}

# prepare [TOOL...]: fails unless qemu-system-arm and each TOOL are installed; with --build,
# then runs firmware-examples/build.sh.
prepare() {
    command -v qemu-system-arm >/dev/null 2>&1 \
        || { echo "$SCRIPT: error: qemu-system-arm not found (apt-get install qemu-system-arm)" >&2; exit 1; }
    local tool
    for tool in "$@"; do
        command -v "$tool" >/dev/null 2>&1 || { echo "$SCRIPT: error: $tool not found" >&2; exit 1; }
    done
    if [ "$BUILD" = 1 ]; then
        "$FW/build.sh" || { echo "$SCRIPT: error: build failed" >&2; exit 1; }
    fi
}

# image -> "triple machine cpu"
board() {
    case "$1" in
        ant-node*) echo "thumbv7m-none-eabi lm3s6965evb cortex-m3" ;;
        bee-node*|fly-node*) echo "thumbv7em-none-eabihf mps2-an386 cortex-m4" ;;
    esac
}

# find_image LABEL IMAGE: sets triple, machine, cpu (see board) and elf (the image under
# firmware-examples/target/); if elf is missing, prints why and counts LABEL as failed (false).
find_image() {
    read -r triple machine cpu <<<"$(board "$2")"
    elf="$FW/target/$triple/release/$2"
    [ -f "$elf" ] && return 0
    failed "$1" "$1: $elf missing (run firmware-examples/build.sh or pass --build)"
    return 1
}

# passed LABEL TEXT / failed LABEL TEXT: prints "ok    TEXT" or "FAIL  TEXT" and counts LABEL.
passed() {
    echo "ok    $2"
    PASSED=$((PASSED + 1))
}
failed() {
    echo "FAIL  $2"
    FAILED=$((FAILED + 1)); FAILURES+=("$1")
}

# What QEMU printed (file $1), less the lm3s6965 timer's chatter.
qemu_output() {
    grep -v '^Timer with period zero, disabling$' "$1"
}

# A string as a JSON string literal.
json_str() {
    printf '"%s"' "$(printf '%s' "$1" | sed 's/\\/\\\\/g; s/"/\\"/g')"
}

# write_runs FILE HEAD: writes HEAD, the JSON objects of JSON (a line each, comma-separated)
# and the counts to FILE.
write_runs() {
    mkdir -p "$(dirname "$1")"
    {
        printf '%s\n' "$2"
        for i in "${!JSON[@]}"; do
            [ "$i" -gt 0 ] && echo ","
            printf '  %s' "${JSON[$i]}"
        done
        printf '\n], "passed": %d, "failed": %d}\n' "$PASSED" "$FAILED"
    } > "$1"
}

# finish [NOTE]: the closing lines ("failed: ..." and "N passed, N failed NOTE"); true only
# if no run failed.
finish() {
    echo
    if [ "$FAILED" -gt 0 ]; then
        echo "${SCRIPT%.sh}: failed: ${FAILURES[*]}"
    fi
    echo "${SCRIPT%.sh}: $PASSED passed, $FAILED failed${1:+ $1}"
    [ "$FAILED" -eq 0 ]
}
