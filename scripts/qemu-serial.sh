#!/usr/bin/env bash
# Runs a serial node image in QEMU with its UART0 on a TCP socket or a pseudo-terminal, and
# optionally talks to it (no swarm-hil needed).
#
#   scripts/qemu-serial.sh [options] IMAGE          one image
#   scripts/qemu-serial.sh --check [options]        all six images: --hello --replay --stack
#
# IMAGE: ant-node, ant-node-fixed (QEMU lm3s6965evb, Cortex-M3) or bee-node, bee-node-fixed,
# fly-node, fly-node-fixed (QEMU mps2-an386, Cortex-M4F):
# firmware-examples/target/<triple>/release/IMAGE.
#
# Where the UART goes:
#   --tcp PORT      a TCP server on 127.0.0.1:PORT (default; PORT 0 or none = a free port)
#   --pty           a pseudo-terminal (its /dev/pts path is printed)
# What to do (without any of these: print where the UART is and run until Ctrl-C/SIGTERM):
#   --hello         send 00 + Hello, check the Identity (protocol 3, name, controller, scalar,
#                   capacities, max_frame, rx_buffer; for ant-node every byte, against
#                   docs/protocol.md section 11), print both
#   --replay FILE   send every request of a transcript (firmware-examples/node/examples/
#                   transcript.rs) and check every reply byte for byte; prints requests/s
#   --steps N       generate a transcript of N ticks for the image (cargo run --example
#                   transcript) and replay it (implies --replay)
#   --window W      requests in flight during a replay (default 1; pipelining, protocol 10.6:
#                   QEMU's UART holds the sender back when full, so the line has flow control
#                   and W is not bound by the Identity's rx_buffer)
#   --stack         after --hello/--replay, read the painted stack's peak through QEMU's
#                   monitor (the images paint the free stack at boot; fw_support::paint_stack);
#                   for a node with a RAM budget (ant-node-fixed 4 KiB, bee-node* 8 KiB,
#                   fly-node* 16 KiB) static RAM + stack peak must fit it
#   --print-cmd     print the QEMU command line and exit
# Other:
#   --build         run firmware-examples/build.sh first
#   --timeout S     per-image limit for --hello/--replay (default 60 s)
#
# QEMU is always stopped on exit (also after an error, Ctrl-C or SIGTERM). Exit status 0 only
# if every check passed. Needs qemu-system-arm and python3.
set -uo pipefail

source "$(dirname "${BASH_SOURCE[0]}")/lib/qemu.sh" qemu-serial.sh
MODE=tcp
PORT=0
HELLO=0
REPLAY=""
STEPS=""
WINDOW=1
STACK=0
PRINT=0
CHECK=0
script_arg() {
    case "$1" in
        --tcp) MODE=tcp; if [[ "${2:-}" =~ ^[0-9]+$ ]]; then PORT=$2; ARGS_USED=2; fi ;;
        --pty) MODE=pty ;;
        --hello) HELLO=1 ;;
        --replay) REPLAY=${2:?--replay needs a transcript file}; ARGS_USED=2 ;;
        --steps) STEPS=${2:?--steps needs a number}; ARGS_USED=2 ;;
        --window) WINDOW=${2:?--window needs a number}; ARGS_USED=2 ;;
        --stack) STACK=1 ;;
        --print-cmd) PRINT=1 ;;
        --check) CHECK=1 ;;
        *) return 1 ;;
    esac
}
parse_args "$@"
if [ "$CHECK" = 1 ]; then
    HELLO=1; STACK=1; [ -n "$STEPS$REPLAY" ] || STEPS=10
    [ ${#SELECTED[@]} -gt 0 ] || SELECTED=("${NODES[@]}")
fi
[ ${#SELECTED[@]} -gt 0 ] || { echo "qemu-serial.sh: name an image (try --help)" >&2; exit 2; }
if [ ${#SELECTED[@]} -gt 1 ] && [ "$HELLO" = 0 ] && [ -z "$REPLAY$STEPS" ] && [ "$PRINT" = 0 ]; then
    echo "qemu-serial.sh: one image at a time without --hello/--replay/--steps" >&2; exit 2
fi
if [ "$MODE" = pty ] && [ "$WINDOW" != 1 ]; then
    echo "qemu-serial.sh: --window needs --tcp" >&2; exit 2
fi

prepare python3

free_port() {
    python3 -c 'import socket; s = socket.socket(); s.bind(("127.0.0.1", 0)); print(s.getsockname()[1])'
}

WORK=$(mktemp -d)
QEMU_PID=""
stop_qemu() {
    if [ -n "$QEMU_PID" ] && kill -0 "$QEMU_PID" 2>/dev/null; then
        kill "$QEMU_PID" 2>/dev/null
        for _ in 1 2 3 4 5 6 7 8 9 10; do kill -0 "$QEMU_PID" 2>/dev/null || break; sleep 0.1; done
        kill -9 "$QEMU_PID" 2>/dev/null
        wait "$QEMU_PID" 2>/dev/null
    fi
    QEMU_PID=""
}
cleanup() { stop_qemu; rm -rf "$WORK"; }
trap cleanup EXIT
trap 'echo; echo "qemu-serial.sh: stopping QEMU"; exit 130' INT
trap 'exit 143' TERM

# A transcript for an image: generated once per image (cargo, host toolchain of the workspace).
transcript() {
    local img=$1 model scalar out="$WORK/$img.transcript"
    model=${img%%-*}
    case "$img" in *-fixed) scalar=fixed ;; *) scalar=f32 ;; esac
    (cd "$FW" && env -u RUSTUP_TOOLCHAIN -u CARGO_TARGET_DIR -u CARGO_BUILD_TARGET -u RUSTFLAGS \
        PATH="/usr/bin:/bin:$PATH" RUSTC=/usr/bin/rustc /usr/bin/cargo run -q --release \
        -p fw-node --example transcript -- "$model" "$scalar" "$STEPS") > "$out" \
        || { echo "qemu-serial.sh: error: generating the transcript failed" >&2; return 1; }
    echo "$out"
}

# The client: --hello / --replay / --stack against a running QEMU.
client() {
    python3 - "$@" <<'PY'
import os, socket, sys, time, termios, tty, select, struct, binascii

args = dict(a.split("=", 1) for a in sys.argv[1:])
img, mode, where = args["image"], args["mode"], args["where"]
deadline = time.time() + float(args["timeout"])
t0 = float(args["t0"])

def fail(msg):
    print(f"FAIL  {img}: {msg}")
    sys.exit(1)

class Line:
    def __init__(self):
        if mode == "tcp":
            host, port = where.rsplit(":", 1)
            while True:
                try:
                    self.s = socket.create_connection((host, int(port)), timeout=1)
                    break
                except OSError:
                    if time.time() > deadline: fail(f"cannot connect to {where}")
                    time.sleep(0.01)
            self.s.setsockopt(socket.IPPROTO_TCP, socket.TCP_NODELAY, 1)
            self.fd = self.s.fileno()
        else:
            self.fd = os.open(where, os.O_RDWR | os.O_NOCTTY)
            tty.setraw(self.fd)
        self.buf = b""
    def send(self, b):
        if mode == "tcp": self.s.sendall(b)
        else:
            while b:
                n = os.write(self.fd, b); b = b[n:]
    def frame(self):
        """The next frame, delimiter included."""
        while b"\x00" not in self.buf:
            left = deadline - time.time()
            if left <= 0: fail("timed out waiting for a reply")
            r, _, _ = select.select([self.fd], [], [], min(left, 1.0))
            if r:
                chunk = os.read(self.fd, 4096)
                if not chunk: fail("the line closed")
                self.buf += chunk
        i = self.buf.index(b"\x00") + 1
        f, self.buf = self.buf[:i], self.buf[i:]
        return f

def cobs_decode(enc):
    out, i = bytearray(), 0
    while i < len(enc):
        code = enc[i]
        if code == 0 or (i + code > len(enc) and code != 1): raise ValueError("COBS")
        out += enc[i + 1:i + code]; i += code
        if code != 0xFF and i < len(enc): out.append(0)
    return bytes(out)

def unframe(f):
    raw = cobs_decode(f[:-1])
    if len(raw) < 6 or struct.unpack("<H", raw[-2:])[0] != binascii.crc_hqx(raw[:-2], 0xFFFF):
        raise ValueError("bad frame " + f.hex(" "))
    return raw[1], struct.unpack("<H", raw[2:4])[0], raw[4:-2]

def varint(b, i):
    v = s = 0
    while True:
        v |= (b[i] & 0x7F) << s; s += 7; i += 1
        if not b[i - 1] & 0x80: return v, i

line = Line()
result = {}

if args.get("hello") == "1":
    hello = bytes.fromhex("00 04 03 01 02 03 4e 4e 00")   # 00, then Hello seq 2 (protocol.md 11)
    line.send(hello)
    reply = line.frame()
    boot_ms = (time.time() - t0) * 1000
    kind, seq, p = unframe(reply)
    if kind != 0x02 or seq != 2: fail(f"expected Identity seq 2, got kind {kind:#x} seq {seq}")
    proto, ctrl, scal, math = p[0], p[1], p[2], p[3]
    i = 4
    caps = []
    for _ in range(4):                             # neighbours, objects, targets, surfaces
        v, i = varint(p, i); caps.append(v)
    max_frame, i = varint(p, i)
    rx_buffer, i = varint(p, i)
    phash, i = varint(p, i)
    n, i = varint(p, i)
    name = p[i:i + n].decode()
    # controller, capacities (neighbours, objects, targets, surfaces), max_frame, rx_buffer (the
    # UART's receive FIFO: PL011 on the lm3s6965evb, CMSDK UART on the mps2-an386)
    want_ctrl, want_caps, want_max, want_rx = {
        "ant": (0, [8, 4, 0, 6], 451, 16),
        "bee": (1, [16, 0, 16, 0], 942, 1),
        "fly": (3, [16, 0, 0, 4], 761, 1),
    }[img.split("-")[0]]
    want_scal = 1 if img.endswith("fixed") else 0
    want_math = 2 if want_scal else 0
    got = (proto, ctrl, scal, math, caps, max_frame, rx_buffer, name)
    want = (3, want_ctrl, want_scal, want_math, want_caps, want_max, want_rx, img)
    if got != want: fail(f"identity {got} != expected {want}")
    if img == "ant-node":
        pinned = bytes.fromhex("04 03 02 02 02 03 01 01 03 08 04 19 06 c3 03 10 c3 8b a1 c0 ec f6 b8 9a 7e"
                               " 08 61 6e 74 2d 6e 6f 64 65 c4 0b 00")
        if reply != pinned: fail("Identity differs from docs/protocol.md section 11")
    print(f"ok    {img}: Hello -> Identity (controller {['Ant','Bee','Wang','Fly'][ctrl]}, scalar "
          f"{['F32','I16F16'][scal]}, math {['Libm','Micromath','Integer'][math]}, capacities {caps}, "
          f"max_frame {max_frame}, rx_buffer {rx_buffer}, params_hash {phash:#018x}, name {name!r}); "
          f"first reply "
          f"{boot_ms:.0f} ms after QEMU started")
    print(f"      host   {hello.hex(' ')}")
    print(f"      device {reply.hex(' ')}")
    result.update(identity_ms=round(boot_ms, 1), params_hash=f"{phash:#018x}", rx_buffer=rx_buffer)

if args.get("replay"):
    pairs = [l.split() for l in open(args["replay"]) if l.strip()]
    window = int(args.get("window", "1"))
    decisions = sum(1 for _, d in pairs if unframe(bytes.fromhex(d))[0] in (0x11, 0x13, 0x21, 0x41))
    t = time.time()
    sent = 0
    for k, (h, d) in enumerate(pairs):
        while sent < len(pairs) and sent < k + window:
            line.send(bytes.fromhex(pairs[sent][0])); sent += 1
        got = line.frame()
        if got != bytes.fromhex(d):
            fail(f"reply {k + 1} of {len(pairs)} differs:\n      request {h}\n      device  "
                 f"{got.hex()}\n      host    {d}")
    dt = time.time() - t
    print(f"ok    {img}: {len(pairs)} replies byte-identical to the host's ({decisions} controller "
          f"decisions) in {dt:.2f} s: {len(pairs) / dt:.0f} requests/s, window {window}")
    result.update(requests=len(pairs), decisions=decisions, seconds=round(dt, 3),
                  requests_per_s=round(len(pairs) / dt, 1))

if args.get("monitor"):
    top, floor, paint = int(args["top"], 16), int(args["floor"], 16), 0xC0FFEE55
    lo = max(floor, top - 32 * 1024)
    lo = (lo + 3) & ~3
    import json
    m = socket.socket(socket.AF_UNIX); m.connect(args["monitor"]); m.settimeout(10)
    mf = m.makefile("rw")
    def qmp(execute, **arguments):
        msg = {"execute": execute}
        if arguments: msg["arguments"] = arguments
        mf.write(json.dumps(msg) + "\n"); mf.flush()
        while True:
            r = json.loads(mf.readline())
            if "return" in r: return r["return"]
            if "error" in r: fail(f"QMP {execute}: {r['error']}")
    json.loads(mf.readline())                      # greeting
    qmp("qmp_capabilities")
    def cmd(c):
        return qmp("human-monitor-command", **{"command-line": c})
    words = []
    addr = lo
    while addr < top:
        n = min(1024, (top - addr) // 4)
        out = cmd(f"xp /{n}wx {addr:#x}")
        vals = []
        for l in out.splitlines():
            l = l.strip()
            if ":" in l and l.split(":")[0].strip().isalnum():
                try: int(l.split(":")[0], 16)
                except ValueError: continue
                vals += [int(x, 16) for x in l.split(":", 1)[1].split()]
        if len(vals) != n: fail(f"monitor read {len(vals)} of {n} words at {addr:#x}")
        words += vals; addr += 4 * n
    k = 0
    while k < len(words) and words[k] == paint: k += 1
    peak = top - (lo + 4 * k)
    capped = k == 0
    print(f"ok    {img}: stack peak {'>=' if capped else ''}{peak} B (painted stack read through the QEMU monitor)")
    result.update(stack_peak=peak)
    budget = int(args.get("ram_budget") or 0)
    if budget:
        ram = peak + floor - int(args["ram_origin"], 16)
        if capped or ram > budget:
            fail(f"static RAM + stack peak {'>=' if capped else ''}{ram} B is over the budget of {budget} B")
        print(f"ok    {img}: static RAM + stack peak {ram} B within the budget of {budget} B")
        result.update(ram_with_stack=ram)

print("RESULT " + " ".join(f"{k}={v}" for k, v in result.items()))
PY
}

# The serial nodes' RAM budgets (README.md "Sizes"), static RAM and stack together; none: empty.
ram_budget() {
    case "$1" in
        ant-node-fixed) echo 4096 ;;
        bee-node|bee-node-fixed) echo 8192 ;;
        fly-node|fly-node-fixed) echo 16384 ;;
    esac
}

sym() {  # sym ELF NAME -> hex address
    local tool
    for tool in llvm-nm nm arm-none-eabi-nm; do
        if command -v "$tool" >/dev/null 2>&1; then
            "$tool" "$1" | awk -v n="$2" '$3 == n { print $1; exit }'
            return
        fi
    done
}

for img in "${SELECTED[@]}"; do
    find_image "$img" "$img" || continue
    trfile="$REPLAY"
    if [ -n "$STEPS" ] && [ "$PRINT" = 0 ]; then
        trfile=$(transcript "$img") || { FAILED=1; continue; }
    fi
    if [ "$MODE" = tcp ]; then
        p=$PORT; [ "$p" = 0 ] && p=$(free_port)
        serial="tcp:127.0.0.1:$p,server=on,wait=off,nodelay=on"
    else
        serial=pty
    fi
    cmd=(qemu-system-arm -machine "$machine" -cpu "$cpu" -display none -monitor none
         -serial "$serial" -kernel "$elf")
    # --stack: QMP on a unix socket, to read the stack through `xp` (human-monitor-command).
    [ "$STACK" = 1 ] && cmd+=(-qmp "unix:$WORK/qmp.sock,server=on,wait=off")
    if [ "$PRINT" = 1 ]; then
        echo "${cmd[*]}"; continue
    fi
    log="$WORK/qemu.log"
    t0=$(python3 -c 'import time; print(time.time())')
    "${cmd[@]}" </dev/null >"$log" 2>&1 &
    QEMU_PID=$!
    if [ "$MODE" = tcp ]; then
        where="127.0.0.1:$p"
    else
        where=""
        for _ in $(seq 100); do
            where=$(sed -n 's/.*char device redirected to \(\/dev\/[^ ]*\) (label serial0).*/\1/p' "$log")
            [ -n "$where" ] && break
            kill -0 "$QEMU_PID" 2>/dev/null || break
            sleep 0.05
        done
        [ -n "$where" ] || { echo "FAIL  $img: QEMU gave no pty"; cat "$log"; FAILED=1; stop_qemu; continue; }
    fi
    echo "==> $img on QEMU $machine (pid $QEMU_PID): UART0 on $MODE $where"
    echo "    ${cmd[*]}"
    if [ "$HELLO" = 0 ] && [ -z "$trfile" ]; then
        echo "    (Ctrl-C or SIGTERM stops QEMU)"
        wait "$QEMU_PID"
        QEMU_PID=""
        continue
    fi
    cargs=(image="$img" mode="$MODE" where="$where" timeout="$TIMEOUT" t0="$t0" hello="$HELLO"
           window="$WINDOW")
    [ -n "$trfile" ] && cargs+=(replay="$trfile")
    if [ "$STACK" = 1 ]; then
        cargs+=(monitor="$WORK/qmp.sock" top="$(sym "$elf" _stack_start)" floor="$(sym "$elf" _stack_end)"
                ram_origin="$(sym "$elf" __sdata)" ram_budget="$(ram_budget "$img")")
    fi
    client "${cargs[@]}" || FAILED=1
    if ! kill -0 "$QEMU_PID" 2>/dev/null; then
        echo "FAIL  $img: QEMU exited early"; qemu_output "$log"; FAILED=1
    fi
    stop_qemu
done
exit $((FAILED > 0))
