#!/usr/bin/env bash
# Runs the firmware self-check images in QEMU and fails if any image fails.
#
#   scripts/qemu-run.sh [--build] [--self-test] [--timeout SECONDS] [IMAGE...]
#
# IMAGE is ant-node, ant-node-fixed, bee-node, bee-node-fixed, fly-node or fly-node-fixed
# (default: all six): the self-check image of that node,
# firmware-examples/target/<triple>/release/<IMAGE>-selfcheck (the `-selfcheck` suffix may be
# given too). Each replays its scenario on the emulated MCU,
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

source "$(dirname "${BASH_SOURCE[0]}")/lib/qemu.sh" qemu-run.sh -selfcheck
SELFTEST=0
parse_args "$@"
[ ${#SELECTED[@]} -gt 0 ] || SELECTED=("${NODES[@]}")
prepare

LOG=$(mktemp)
trap 'rm -f "$LOG"' EXIT

# run_one <image> <expect: pass|fail> [semihosting args...]
run_one() {
    local img=$1 expect=$2; shift 2
    local triple machine cpu elf rc semi label
    label="$img"; [ "$expect" = fail ] && label="$img (self-test: corrupted expectation)"
    find_image "$label" "$img-selfcheck" || return
    semi="enable=on,target=native"
    for a in "$@"; do semi="$semi,arg=$a"; done
    timeout "$TIMEOUT" qemu-system-arm -machine "$machine" -cpu "$cpu" -nographic -monitor none \
        -semihosting-config "$semi" -kernel "$elf" </dev/null >"$LOG" 2>&1
    rc=$?
    local out
    out=$(qemu_output "$LOG")
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
        passed "$label" "$label ($why)"
    else
        failed "$label" "$label ($why, expected $( [ "$expect" = pass ] && echo 'exit 0 and PASS' || echo 'non-zero exit and FAIL'))"
    fi
    printf '%s\n' "$out" | sed 's/^/      | /'
    local peak
    peak=$(printf '%s\n' "$summary" | sed -n 's/.*stack peak >\{0,1\}=\{0,1\}\([0-9]*\) B.*/\1/p')
    JSON+=("$(printf '{"image": "%s", "machine": "%s", "expect": "%s", "exit": %d, "ok": %s, "stack_peak": %s, "summary": %s}' \
        "$img" "$machine" "$expect" "$rc" "$( [ $ok = 1 ] && echo true || echo false)" "${peak:-null}" "$(json_str "$summary")")")
}

for img in "${SELECTED[@]}"; do
    run_one "$img" pass
    if [ "$SELFTEST" = 1 ]; then
        run_one "$img" fail "$img" corrupt
    fi
done

write_runs "$FW/target/qemu-results.json" '{"runs": ['
finish
