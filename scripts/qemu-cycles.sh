#!/usr/bin/env bash
# Measures what one controller step costs on the emulated Cortex-M cores, in instructions: runs
# the measurement images in QEMU with -icount, converts their SysTick ticks to instructions,
# cross-checks the conversion, prints a table and fails if any image fails.
#
#   scripts/qemu-cycles.sh [--build] [--self-test] [--shift N] [--timeout SECONDS] [IMAGE...]
#
# IMAGE is ant-node, ant-node-fixed, bee-node, bee-node-fixed, fly-node or fly-node-fixed
# (default: all six): the measurement image of that node,
# firmware-examples/target/<triple>/release/<IMAGE>-cycles (the `-cycles` suffix may be given
# too). Each times its controller call by call as the serial node runs it (ant: plan_checked
# and resolve_checked per ant-step, 24 ants × 16 ticks; bee: step_checked, 20 bees × 16 steps;
# fly: step_checked, 24 insects × 16 steps; see fw_support::cycles and fw_scenario's `cost`),
# with SysTick on the processor clock, and prints one line of ticks over semihosting.
#
# Conversion: QEMU runs with `-icount shift=N` (default 7), so virtual time advances exactly
# 2^N ns per guest instruction, and SysTick counts virtual time at the board's system clock
# clk_hz (printed by the image: lm3s6965evb 12.5 MHz from its SYSCTL RCC, mps2-an386 25 MHz):
#     instructions = ticks × (1e9 / clk_hz) / 2^N
# At shift 0 SysTick would tick once per 80 (lm3s) or 40 (mps2) instructions; at 7 it ticks
# 1.6 or 3.2 times per instruction, and a 24-bit wrap is still over 5 million instructions away.
# Cross-check: each image also times two counted loops (`subs; bne` and `nop; nop; subs; bne`,
# 1,000 and 11,000 iterations); the converted difference must be 20,000 and 40,000
# instructions within 1 %, or the run fails.
#
#   --build      run firmware-examples/build.sh first (otherwise the images must exist)
#   --self-test  also run each image with QEMU at shift N+1 while converting at shift N: the
#                cross-check must then FAIL (proves it can fail)
#   --shift N    icount shift (0-10; default 7)
#   --timeout S  per-run limit (default 60 s); a hang counts as a failure
#
# Results: a table, a closing "N passed, N failed" line, and firmware-examples/target/cycles.json.
# Exit status 0 only if every run went as expected. Instruction counts are QEMU's (each guest
# instruction counts 1); they are not cycles on silicon (see docs/benchmarks.md).
set -uo pipefail

source "$(dirname "${BASH_SOURCE[0]}")/lib/qemu.sh" qemu-cycles.sh -cycles
SHIFT=7
SELFTEST=0
TOLERANCE_PCT=1
script_arg() {
    case "$1" in
        --shift) SHIFT=${2:?--shift needs a number}; ARGS_USED=2 ;;
        *) return 1 ;;
    esac
}
parse_args "$@"
[ ${#SELECTED[@]} -gt 0 ] || SELECTED=("${NODES[@]}")
case "$SHIFT" in
    [0-9]|10) ;;
    *) echo "qemu-cycles.sh: --shift must be 0-10 (got '$SHIFT')" >&2; exit 2 ;;
esac
if [ "$SELFTEST" = 1 ] && [ "$SHIFT" -ge 10 ]; then
    echo "qemu-cycles.sh: --self-test needs --shift below 10" >&2; exit 2
fi
prepare
QEMU_VERSION=$(qemu-system-arm --version | sed -n '1s/^QEMU emulator version \([^ ]*\).*/\1/p')

# Reads the image's line on stdin; prints, tab-separated:
#   CAL <loop> <expected> <measured> <error %> <ok 0|1>
#   PHASE <name> <n> <min> <mean> <max>         (instructions)
#   INFO <key> <value>
#   STATUS <ok 0|1> <why>
# shift = the shift to convert with; tol = the cross-check's tolerance in percent.
CONVERT='
function num(s) { return s + 0 }
{
    for (i = 2; i <= NF; i++) {
        eq = index($i, "=")
        if (eq > 0) v[substr($i, 1, eq - 1)] = substr($i, eq + 1)
    }
}
END {
    OFS = "\t"
    why = ""
    if (!("clk_hz" in v) || num(v["clk_hz"]) <= 0) { print "STATUS", 0, "no clk_hz in the line"; exit }
    f = (1e9 / num(v["clk_hz"])) / (2 ^ shift)          # instructions per tick
    print "INFO", "instructions_per_tick", sprintf("%.6f", f)
    ok = 1
    for (k = 1; k <= 2; k++) {
        loop = k == 1 ? "spin2" : "spin4"; per = k == 1 ? 2 : 4
        if (!(loop in v) || split(v[loop], a, ",") != 2 || split(a[1], p, ":") != 2 || split(a[2], q, ":") != 2) {
            print "STATUS", 0, "no " loop " calibration in the line"; exit
        }
        expect = per * (q[1] - p[1]); meas = (q[2] - p[2]) * f
        err = (meas - expect) / expect * 100
        if (sprintf("%.3f", err) + 0 == 0) err = 0
        good = (err <= tol && err >= -tol)
        if (!good) { ok = 0; why = why " " loop " off by " sprintf("%+.2f", err) " %" }
        print "CAL", loop, expect, sprintf("%.1f", meas), sprintf("%+.3f", err), good
    }
    nph = split("plan resolve step moving", names, " ")
    for (k = 1; k <= nph; k++) {
        if (!(names[k] in v)) continue
        if (split(v[names[k]], s, ":") != 4 || num(s[1]) == 0) { ok = 0; why = why " empty " names[k]; continue }
        print "PHASE", names[k], s[1], sprintf("%.0f", s[2] * f), sprintf("%.1f", s[4] / s[1] * f), sprintf("%.0f", s[3] * f)
    }
    if (!("step" in v)) { ok = 0; why = why " no step figures" }
    split("overhead dwt_ctrl dwt_cyccnt neighbours targets surfaces full_frames avoiding infeasible errors overflows", keys, " ")
    for (k in keys) if (keys[k] in v) print "INFO", keys[k], v[keys[k]]
    # overflows= comes last: without it the line was cut short.
    if (!("errors" in v) || !("overflows" in v)) { ok = 0; why = why " incomplete line" }
    if (num(v["errors"]) != 0) { ok = 0; why = why " controller errors" }
    if (num(v["overflows"]) != 0) { ok = 0; why = why " timer overflows" }
    sub(/^ /, "", why)
    print "STATUS", ok, why
}'

ROWS=()
LOG=$(mktemp)
trap 'rm -f "$LOG"' EXIT

# run_one <image> <expect: pass|fail> <shift QEMU runs with>
run_one() {
    local img=$1 expect=$2 run_shift=$3
    local triple machine cpu elf rc label
    label="$img-cycles"
    [ "$expect" = fail ] && label="$img-cycles (self-test: QEMU at shift $run_shift, converted at $SHIFT)"
    find_image "$label" "$img-cycles" || return
    timeout "$TIMEOUT" qemu-system-arm -machine "$machine" -cpu "$cpu" -nographic -monitor none \
        -icount "shift=$run_shift" -semihosting-config enable=on,target=native \
        -kernel "$elf" </dev/null >"$LOG" 2>&1
    rc=$?
    local line parsed status ok why
    line=$(grep -m1 '^cycles ' "$LOG")
    if [ -n "$line" ]; then
        parsed=$(printf '%s\n' "$line" | awk -v shift="$SHIFT" -v tol="$TOLERANCE_PCT" "$CONVERT")
    else
        parsed=$(printf 'STATUS\t0\tno "cycles" line\n')
    fi
    status=$(printf '%s\n' "$parsed" | awk -F'\t' '$1 == "STATUS"')
    ok=$(printf '%s\n' "$status" | cut -f2)
    why=$(printf '%s\n' "$status" | cut -f3)
    local good=0
    if [ "$expect" = pass ]; then
        [ $rc -eq 0 ] && [ "$ok" = 1 ] && good=1
    else
        # The run itself must work; only the cross-check may fail.
        [ $rc -eq 0 ] && [ "$ok" = 0 ] && printf '%s\n' "$why" | grep -q 'off by' && good=1
    fi
    local what="exit $rc"
    [ $rc -eq 124 ] && what="timed out after ${TIMEOUT}s"
    [ -n "$why" ] && what="$what; $why"
    if [ $good = 1 ]; then
        passed "$label" "$label ($what)"
    else
        failed "$label" "$label ($what; expected $( [ "$expect" = pass ] && echo 'exit 0 and the cross-check within '"$TOLERANCE_PCT"' %' || echo 'exit 0 and a failed cross-check'))"
        qemu_output "$LOG" | sed 's/^/      | /'
    fi
    [ "$expect" = pass ] || return 0
    [ -n "$line" ] || return 0

    local scalar cal phases info
    scalar=$(printf '%s\n' "$line" | tr ' ' '\n' | sed -n 's/^scalar=//p')
    cal=$(printf '%s\n' "$parsed" | awk -F'\t' '$1 == "CAL" {
        printf "%s{\"loop\": \"%s\", \"expected\": %s, \"measured\": %s, \"error_pct\": %s, \"ok\": %s}",
            (n++ ? ", " : ""), $2, $3, $4, $5 + 0, ($6 == 1 ? "true" : "false") }')
    phases=$(printf '%s\n' "$parsed" | awk -F'\t' '$1 == "PHASE" {
        printf "%s\"%s\": {\"n\": %s, \"min\": %s, \"mean\": %s, \"max\": %s}", (n++ ? ", " : ""), $2, $3, $4, $5, $6 }')
    info=$(printf '%s\n' "$parsed" | awk -F'\t' '$1 == "INFO" {
        v = $3; if (v !~ /^[0-9.]+$/) v = "\"" v "\""
        printf "%s\"%s\": %s", (n++ ? ", " : ""), $2, v }')
    JSON+=("$(printf '{"image": "%s-cycles", "machine": "%s", "cpu": "%s", "scalar": "%s", "exit": %d, "ok": %s, "calibration": [%s], "instructions": {%s}, "info": {%s}, "line": %s}' \
        "$img" "$machine" "$cpu" "$scalar" "$rc" "$( [ $good = 1 ] && echo true || echo false)" \
        "$cal" "$phases" "$info" "$(json_str "$line")")")
    local cal_txt dwt_txt
    cal_txt=$(printf '%s\n' "$parsed" | awk -F'\t' '$1 == "CAL" { printf "%s%s %s→%s (%s %%)", (n++ ? ", " : ""), $2, $3, $4, $5 }')
    dwt_txt=$(printf '%s\n' "$parsed" | awk -F'\t' '$1 == "INFO" && $2 ~ /^dwt/ { printf "%s%s=%s", (n++ ? " " : ""), $2, $3 }')
    local names
    names=$(printf '%s\n' "$parsed" | awk -F'\t' -v img="$img" -v cpu="$cpu" -v scalar="$scalar" '$1 == "PHASE" {
        name = $2
        if (img ~ /^ant/ && name == "step") name = "ant-step"
        else if (img ~ /^ant/ && name == "moving") name = "ant-step, moving ants"
        else if (img ~ /^bee/ && name == "step") name = "bee-step"
        else if (img ~ /^fly/ && name == "step") name = "fly-step"
        printf "  %-24s %-10s %-7s %-22s %5s %8s %10s %8s\n", img "-cycles", cpu, scalar, name, $3, $4, $5, $6 }')
    ROWS+=("$names"$'\n'"    cross-check: $cal_txt; $dwt_txt")
}

for img in "${SELECTED[@]}"; do
    run_one "$img" pass "$SHIFT"
    if [ "$SELFTEST" = 1 ]; then
        run_one "$img" fail $((SHIFT + 1))
    fi
done

if [ ${#ROWS[@]} -gt 0 ]; then
    echo
    echo "Instructions per call (QEMU $QEMU_VERSION, -icount shift=$SHIFT; min / mean / max over the calls):"
    printf '  %-24s %-10s %-7s %-22s %5s %8s %10s %8s\n' image cpu scalar phase n min mean max
    for r in "${ROWS[@]}"; do printf '%s\n' "$r"; done
fi

write_runs "$FW/target/cycles.json" "$(printf '{"qemu": "%s", "icount_shift": %d, "tolerance_pct": %s, "instructions": "ticks * (1e9 / clk_hz) / 2^icount_shift", "runs": [' \
    "$QEMU_VERSION" "$SHIFT" "$TOLERANCE_PCT")"
finish "(firmware-examples/target/cycles.json)"
