#!/usr/bin/env bash
# Builds the firmware images (serial nodes and self-checks) and reports their sizes.
#
#   firmware-examples/build.sh [--fetch] [--offline] [--enforce-budgets] [--only ant|bee|fly]
#
# Images (ELF, under firmware-examples/target/<triple>/release/):
#   ant-node                  thumbv7m-none-eabi     QEMU lm3s6965evb (Cortex-M3)   f32 (libm)
#   ant-node-fixed            thumbv7m-none-eabi     QEMU lm3s6965evb (Cortex-M3)   Fx (I16F16)
#   bee-node                  thumbv7em-none-eabihf  QEMU mps2-an386  (Cortex-M4F)  f32 (libm)
#   bee-node-fixed            thumbv7em-none-eabihf  QEMU mps2-an386  (Cortex-M4F)  Fx (I16F16)
#   fly-node                  thumbv7em-none-eabihf  QEMU mps2-an386  (Cortex-M4F)  f32 (libm)
#   fly-node-fixed            thumbv7em-none-eabihf  QEMU mps2-an386  (Cortex-M4F)  Fx (I16F16)
# are the serial nodes (the device endpoint on UART0; scripts/qemu-serial.sh runs them), and
#   ant-node-selfcheck, ant-node-fixed-selfcheck, bee-node-selfcheck, bee-node-fixed-selfcheck,
#   fly-node-selfcheck, fly-node-fixed-selfcheck
# the self-check images (replay a scenario, compare with the host; scripts/qemu-run.sh), and
#   ant-node-cycles, ant-node-fixed-cycles, bee-node-cycles, bee-node-fixed-cycles,
#   fly-node-cycles, fly-node-fixed-cycles
# the measurement images (time the controller call by call; scripts/qemu-cycles.sh).
# (ant-node-other, bee-node-other and fly-node-other serve other parameters:
# scripts/hil-qemu.sh's refusal test.)
#
# Toolchain, per target: rustup's cargo if `rustup target list --installed` has the target;
# otherwise Debian's rustc/cargo (packages rustc-web cargo-web rust-web-src lld) with
# RUSTC_BOOTSTRAP=1 -Z build-std=core, linked by ld.lld when rust-lld is not in that sysroot.
# FW_TOOLCHAIN=rustup|debian forces one route.
#
# The first build needs crates.io (our crates, and for the Debian route the crates of the std
# library workspace that -Z build-std resolves). `build.sh --fetch` downloads all of them and
# exits; after that `build.sh --offline` (or plain build.sh) needs no network.
#
# Sizes go to firmware-examples/target/sizes.json (and a table on stdout):
#   flash      = .vector_table + .text + .rodata + .data (the initial values of .data live in flash)
#   ram_static = .data + .bss + .uninit (the stack is not included; qemu-run.sh reports its peak)
# Budgets (see README.md), for the serial nodes: ant-node-fixed <= 16 KiB flash / 4 KiB RAM;
# bee-node, bee-node-fixed <= 32 KiB / 8 KiB; fly-node, fly-node-fixed <= 48 KiB / 16 KiB (RAM
# including the stack: static RAM is checked here, static RAM + stack peak by
# scripts/qemu-serial.sh --stack). The self-check images carry their scenario and
# its expected-decision table on top, the measurement images their scenario and timing code;
# neither has a budget.
# Over budget is a warning, or an error with --enforce-budgets (or FW_ENFORCE_BUDGETS=1).
set -euo pipefail

HERE=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
cd "$HERE"

OFFLINE=()
FETCH=0
ENFORCE=${FW_ENFORCE_BUDGETS:-0}
ONLY=""
while [ $# -gt 0 ]; do
    case "$1" in
        --offline) OFFLINE=(--offline) ;;
        --fetch) FETCH=1 ;;
        --enforce-budgets) ENFORCE=1 ;;
        --only) ONLY=${2:?--only needs ant, bee or fly}; shift ;;
        -h|--help) awk 'NR > 1 && /^set /{exit} NR > 1' "$HERE/build.sh"; exit 0 ;;
        *) echo "build.sh: unknown argument '$1' (try --help)" >&2; exit 2 ;;
    esac
    shift
done

# A cargo/rustc environment inherited from a calling cargo (e.g. the top-level test suite) must
# not leak into this separate workspace.
unset CARGO_TARGET_DIR CARGO_BUILD_TARGET CARGO_BUILD_TARGET_DIR RUSTFLAGS CARGO_ENCODED_RUSTFLAGS \
      RUSTDOCFLAGS RUSTC_WRAPPER RUSTC_WORKSPACE_WRAPPER CARGO_MAKEFLAGS MAKEFLAGS MFLAGS \
      CARGO_MANIFEST_DIR CARGO_PKG_NAME CARGO_PRIMARY_PACKAGE CARGO OUT_DIR TARGET HOST \
      CARGO_BUILD_RUSTC CARGO_BUILD_RUSTC_WRAPPER RUSTC RUSTDOC 2>/dev/null || true

TARGET_DIR="$HERE/target"
DEBIAN_RUSTC=/usr/bin/rustc
DEBIAN_CARGO=/usr/bin/cargo

die() { echo "build.sh: error: $*" >&2; exit 1; }
case "$ONLY" in
    ""|ant|bee|fly) ;;
    *) die "--only takes ant, bee or fly (got '$ONLY')" ;;
esac

# The toolchain rustup would use here (empty without rustup).
rustup_toolchain() {
    command -v rustup >/dev/null 2>&1 || return 0
    (cd "$HERE" && rustup show active-toolchain 2>/dev/null) | awk 'NR == 1 { print $1 }'
}

rustup_has_target() {
    local tc
    tc=$(rustup_toolchain)
    [ -n "$tc" ] || return 1
    rustup target list --installed --toolchain "$tc" 2>/dev/null | grep -qx "$1"
}

debian_usable() {
    [ -x "$DEBIAN_RUSTC" ] && [ -x "$DEBIAN_CARGO" ] || return 1
    local sysroot
    sysroot=$("$DEBIAN_RUSTC" --print sysroot 2>/dev/null) || return 1
    [ -f "$sysroot/lib/rustlib/src/rust/library/core/Cargo.toml" ]
}

# Prints the linker to use with the Debian rustc (empty: its default rust-lld exists).
debian_linker() {
    local sysroot host
    sysroot=$("$DEBIAN_RUSTC" --print sysroot)
    host=$("$DEBIAN_RUSTC" -vV | sed -n 's/^host: //p')
    if [ -x "$sysroot/lib/rustlib/$host/bin/rust-lld" ]; then
        echo ""
    elif command -v ld.lld >/dev/null 2>&1; then
        command -v ld.lld
    else
        return 1
    fi
}

# build <package> <triple>
build() {
    local pkg=$1 triple=$2 route=${FW_TOOLCHAIN:-auto}
    local var
    var=CARGO_TARGET_$(echo "$triple" | tr 'a-z-' 'A-Z_')_LINKER
    if [ "$route" = auto ]; then
        if rustup_has_target "$triple"; then route=rustup
        elif debian_usable; then route=debian
        else
            die "no toolchain can build $triple: either 'rustup target add $triple' (rustup's
       cargo is then used), or install Debian's rustc-web cargo-web rust-web-src lld
       (apt-get install rustc-web cargo-web rust-web-src lld) for the -Z build-std=core route."
        fi
    fi
    echo "==> $pkg for $triple (toolchain: $route)"
    case "$route" in
        rustup)
            local tc
            tc=$(rustup_toolchain)
            [ -n "$tc" ] || die "FW_TOOLCHAIN=rustup but rustup has no active toolchain"
            rustup run "$tc" cargo build --release "${OFFLINE[@]}" --target-dir "$TARGET_DIR" -p "$pkg" --target "$triple" \
                || die "cargo (rustup) failed to build $pkg for $triple"
            ;;
        debian)
            debian_usable || die "Debian toolchain incomplete: need $DEBIAN_RUSTC, $DEBIAN_CARGO and
       rust-src in its sysroot (apt-get install rustc-web cargo-web rust-web-src)"
            local linker
            linker=$(debian_linker) || die "no linker for $triple: rust-lld is not in the Debian
       sysroot and ld.lld is not installed (apt-get install lld)"
            # rustup's proxies in ~/.cargo/bin must not shadow the Debian binaries.
            env -u RUSTUP_TOOLCHAIN PATH="/usr/bin:/bin:$PATH" RUSTC="$DEBIAN_RUSTC" RUSTC_BOOTSTRAP=1 \
                ${linker:+"$var=$linker"} \
                "$DEBIAN_CARGO" build --release "${OFFLINE[@]}" --target-dir "$TARGET_DIR" \
                -p "$pkg" --target "$triple" \
                -Z build-std=core -Z build-std-features=compiler-builtins-mem \
                || die "cargo (Debian, -Z build-std=core) failed to build $pkg for $triple"
            ;;
        *) die "FW_TOOLCHAIN must be rustup, debian or auto (got '$route')" ;;
    esac
}

if [ "$FETCH" = 1 ]; then
    echo "==> fetching crates (workspace deps; std-library deps for -Z build-std)"
    cargo_route=${FW_TOOLCHAIN:-auto}
    tc=$(rustup_toolchain)
    if [ "$cargo_route" != debian ] && [ -n "$tc" ]; then
        rustup run "$tc" cargo fetch || die "cargo fetch failed"
    fi
    if [ "$cargo_route" != rustup ] && debian_usable; then
        env -u RUSTUP_TOOLCHAIN PATH="/usr/bin:/bin:$PATH" RUSTC="$DEBIAN_RUSTC" RUSTC_BOOTSTRAP=1 \
            "$DEBIAN_CARGO" fetch --target thumbv7m-none-eabi --target thumbv7em-none-eabihf \
            -Z build-std=core || die "cargo fetch (Debian, -Z build-std=core) failed"
    fi
    echo "fetched: later builds work offline (build.sh --offline)"
    exit 0
fi

# node <package> <triple> <board> <budget of the f32 node> <budget of the fixed node>: builds the
# package and lists its images (a budget is "flash ram" in bytes, or "- -" for none).
IMAGES=()
node() {
    local pkg=$1 triple=$2 board=$3
    build "$pkg" "$triple"
    IMAGES+=("$pkg $triple $board f32 $4"
             "$pkg-fixed $triple $board I16F16 $5"
             "$pkg-selfcheck $triple $board f32 - -"
             "$pkg-fixed-selfcheck $triple $board I16F16 - -"
             "$pkg-other $triple $board f32 - -"
             "$pkg-cycles $triple $board f32 - -"
             "$pkg-fixed-cycles $triple $board I16F16 - -")
}
if [ -z "$ONLY" ] || [ "$ONLY" = ant ]; then
    node ant-node thumbv7m-none-eabi lm3s6965evb "- -" "16384 4096"
fi
if [ -z "$ONLY" ] || [ "$ONLY" = bee ]; then
    node bee-node thumbv7em-none-eabihf mps2-an386 "32768 8192" "32768 8192"
fi
if [ -z "$ONLY" ] || [ "$ONLY" = fly ]; then
    node fly-node thumbv7em-none-eabihf mps2-an386 "49152 16384" "49152 16384"
fi

# --- sizes ------------------------------------------------------------------------------------
# Prints "name size" per allocated section of an ELF.
sections() {
    local elf=$1 tool
    for tool in ${FW_SIZE_TOOL:-llvm-size rust-size arm-none-eabi-size}; do
        if command -v "$tool" >/dev/null 2>&1; then
            "$tool" -A "$elf" | awk 'NR > 2 && $1 ~ /^\./ { print $1, $2 }'
            return
        fi
    done
    local readelf
    readelf=$(command -v llvm-readelf || command -v readelf || command -v arm-none-eabi-readelf) \
        || die "no size tool: install llvm (llvm-size), binutils-arm-none-eabi or binutils (readelf)"
    # readelf -SW: [Nr] Name Type Address Off Size ...  (sizes in hex)
    local name size
    "$readelf" -SW "$elf" | sed 's/^ *\[ *[0-9]*\] *//' | awk '$1 ~ /^\./ { print $1, $5 }' |
        while read -r name size; do echo "$name $((16#$size))"; done
}

SIZES="$TARGET_DIR/sizes.json"
OVER=0
{
    echo "{"
    echo "  \"flash\": \".vector_table + .text + .rodata + .data\","
    echo "  \"ram_static\": \".data + .bss + .uninit (stack excluded)\","
    echo "  \"images\": ["
} > "$SIZES.tmp"
printf '\n%-25s %-22s %-12s %-7s %8s %8s %8s %8s %8s %10s %10s\n' image target board scalar \
    vectors text rodata data bss FLASH RAM
first=1
for spec in "${IMAGES[@]}"; do
    read -r name triple board scalar bflash bram <<<"$spec"
    elf="$TARGET_DIR/$triple/release/$name"
    [ -f "$elf" ] || die "expected image $elf was not built"
    declare -A s=([.vector_table]=0 [.text]=0 [.rodata]=0 [.data]=0 [.bss]=0 [.uninit]=0)
    while read -r sec size; do
        [ -n "${s[$sec]+x}" ] && s[$sec]=$size
    done < <(sections "$elf")
    flash=$(( s[.vector_table] + s[.text] + s[.rodata] + s[.data] ))
    ram=$(( s[.data] + s[.bss] + s[.uninit] ))
    verdict=""
    if [ "$bflash" != - ] && { [ "$flash" -gt "$bflash" ] || [ "$ram" -gt "$bram" ]; }; then
        verdict="  OVER BUDGET (flash <= $bflash, RAM <= $bram)"; OVER=1
    elif [ "$bflash" != - ]; then
        verdict="  (budget $((bflash / 1024)) KiB / $((bram / 1024)) KiB: ok)"
    fi
    printf '%-25s %-22s %-12s %-7s %8d %8d %8d %8d %8d %10d %10d%s\n' "$name" "$triple" "$board" \
        "$scalar" "${s[.vector_table]}" "${s[.text]}" "${s[.rodata]}" "${s[.data]}" "${s[.bss]}" \
        "$flash" "$ram" "$verdict"
    [ $first = 1 ] || echo "," >> "$SIZES.tmp"
    first=0
    jb() { [ "$1" = - ] && echo null || echo "$1"; }
    printf '    {"name": "%s", "target": "%s", "board": "%s", "scalar": "%s", "elf": "%s", "vector_table": %d, "text": %d, "rodata": %d, "data": %d, "bss": %d, "uninit": %d, "flash": %d, "ram_static": %d, "budget_flash": %s, "budget_ram": %s}' \
        "$name" "$triple" "$board" "$scalar" "firmware-examples/target/$triple/release/$name" \
        "${s[.vector_table]}" "${s[.text]}" "${s[.rodata]}" "${s[.data]}" "${s[.bss]}" "${s[.uninit]}" \
        "$flash" "$ram" "$(jb "$bflash")" "$(jb "$bram")" >> "$SIZES.tmp"
    unset s
done
printf '\n  ]\n}\n' >> "$SIZES.tmp"
mv "$SIZES.tmp" "$SIZES"

echo
echo "Images:"
for spec in "${IMAGES[@]}"; do
    read -r name triple _ <<<"$spec"
    echo "  $TARGET_DIR/$triple/release/$name"
done
echo "Sizes: $SIZES"
if [ "$OVER" = 1 ]; then
    if [ "$ENFORCE" = 1 ]; then die "an image is over its size budget (see the table above)"; fi
    echo "build.sh: warning: an image is over its size budget (see the table above)" >&2
fi
