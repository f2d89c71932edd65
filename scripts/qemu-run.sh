#!/usr/bin/env bash
# Runs the firmware self-check images in QEMU and fails if any image fails.
#
#   scripts/qemu-run.sh [--build] [--self-test] [--timeout SECONDS] [IMAGE...]
#
# IMAGE is ant-node, ant-node-fixed, bee-node or bee-node-fixed (default: all four): the
# self-check image of that node, firmware-examples/target/<triple>/release/<IMAGE>-selfcheck
# (the `-selfcheck` suffix may be given too). Each replays its scenario on the emulated MCU,
# compares every decision word bit for bit with the values the host computed at build time,
# prints one line over semihosting and exits QEMU with status 0 only if all matched.
# (The serial node images themselves, without the suffix, run with scripts/qemu-serial.sh.)
#
#   --build      run firmware-examples/build.sh first (otherwise the images must exist)
#   --self-test  also run each image with the semihosting argument `corrupt`: the image flips
#                one bit of one expected word and must then FAIL (proves the check can fail)
#   --timeout S  per-run limit (default 60 s); a hang counts as a failure
#
# Results: a line per run, a closing "N passed, N failed" line, and
# firmware-examples/target/qemu-results.json. Exit status 0 only if every run went as expected.
set -uo pipefail

ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
FW="$ROOT/firmware-examples"
TIMEOUT=60
BUILD=0
SELFTEST=0
SELECTED=()
while [ $# -gt 0 ]; do
    case "$1" in
        --build) BUILD=1 ;;
        --self-test) SELFTEST=1 ;;
        --timeout) TIMEOUT=${2:?--timeout needs seconds}; shift ;;
        -h|--help) awk 'NR > 1 && /^set /{exit} NR > 1' "$0"; exit 0 ;;
        ant-node|ant-node-fixed|bee-node|bee-node-fixed) SELECTED+=("$1") ;;
        ant-node-selfcheck|ant-node-fixed-selfcheck|bee-node-selfcheck|bee-node-fixed-selfcheck)
            SELECTED+=("${1%-selfcheck}") ;;
        *) echo "qemu-run.sh: unknown argument '$1' (try --help)" >&2; exit 2 ;;
    esac
    shift
done
[ ${#SELECTED[@]} -gt 0 ] || SELECTED=(ant-node ant-node-fixed bee-node bee-node-fixed)

command -v qemu-system-arm >/dev/null 2>&1 \
    || { echo "qemu-run.sh: error: qemu-system-arm not found (apt-get install qemu-system-arm)" >&2; exit 1; }

if [ "$BUILD" = 1 ]; then
    "$FW/build.sh" || { echo "qemu-run.sh: error: build failed" >&2; exit 1; }
fi

# image -> "triple machine cpu"
board() {
    case "$1" in
        ant-node*) echo "thumbv7m-none-eabi lm3s6965evb cortex-m3" ;;
        bee-node*) echo "thumbv7em-none-eabihf mps2-an386 cortex-m4" ;;
    esac
}

PASSED=0
FAILED=0
FAILURES=()
JSON=()
LOG=$(mktemp)
trap 'rm -f "$LOG"' EXIT

# run_one <image> <expect: pass|fail> [semihosting args...]
run_one() {
    local img=$1 expect=$2; shift 2
    local triple machine cpu elf rc semi label
    read -r triple machine cpu <<<"$(board "$img")"
    elf="$FW/target/$triple/release/$img-selfcheck"
    label="$img"; [ "$expect" = fail ] && label="$img (self-test: corrupted expectation)"
    if [ ! -f "$elf" ]; then
        echo "FAIL  $label: $elf missing (run firmware-examples/build.sh or pass --build)"
        FAILED=$((FAILED + 1)); FAILURES+=("$label"); return
    fi
    semi="enable=on,target=native"
    for a in "$@"; do semi="$semi,arg=$a"; done
    timeout "$TIMEOUT" qemu-system-arm -machine "$machine" -cpu "$cpu" -nographic -monitor none \
        -semihosting-config "$semi" -kernel "$elf" </dev/null >"$LOG" 2>&1
    rc=$?
    # Drop QEMU's lm3s6965 timer chatter; keep everything the image printed.
    local out
    out=$(grep -v '^Timer with period zero, disabling$' "$LOG")
    local summary
    summary=$(printf '%s\n' "$out" | grep -E ': (PASS|FAIL) ' | head -n1)
    local ok=0
    if [ "$expect" = pass ]; then
        [ $rc -eq 0 ] && printf '%s\n' "$out" | grep -q ': PASS ' && ok=1
    else
        [ $rc -ne 0 ] && [ $rc -ne 124 ] && printf '%s\n' "$out" | grep -q ': FAIL ' && ok=1
    fi
    local why="exit $rc"
    [ $rc -eq 124 ] && why="timed out after ${TIMEOUT}s"
    if [ $ok = 1 ]; then
        echo "ok    $label ($why)"
        PASSED=$((PASSED + 1))
    else
        echo "FAIL  $label ($why, expected $( [ "$expect" = pass ] && echo 'exit 0 and PASS' || echo 'non-zero exit and FAIL'))"
        FAILED=$((FAILED + 1)); FAILURES+=("$label")
    fi
    printf '%s\n' "$out" | sed 's/^/      | /'
    local peak
    peak=$(printf '%s\n' "$summary" | sed -n 's/.*stack peak >\{0,1\}=\{0,1\}\([0-9]*\) B.*/\1/p')
    local esc
    esc=$(printf '%s' "$summary" | sed 's/\\/\\\\/g; s/"/\\"/g')
    JSON+=("$(printf '{"image": "%s", "machine": "%s", "expect": "%s", "exit": %d, "ok": %s, "stack_peak": %s, "summary": "%s"}' \
        "$img" "$machine" "$expect" "$rc" "$( [ $ok = 1 ] && echo true || echo false)" "${peak:-null}" "$esc")")
}

for img in "${SELECTED[@]}"; do
    run_one "$img" pass
    if [ "$SELFTEST" = 1 ]; then
        run_one "$img" fail "$img" corrupt
    fi
done

mkdir -p "$FW/target"
{
    echo "{\"runs\": ["
    for i in "${!JSON[@]}"; do
        [ "$i" -gt 0 ] && echo ","
        printf '  %s' "${JSON[$i]}"
    done
    printf '\n], "passed": %d, "failed": %d}\n' "$PASSED" "$FAILED"
} > "$FW/target/qemu-results.json"

echo
if [ "$FAILED" -gt 0 ]; then
    echo "qemu-run: failed: ${FAILURES[*]}"
fi
echo "qemu-run: $PASSED passed, $FAILED failed"
[ "$FAILED" -eq 0 ]
