#!/usr/bin/env bash
# R-T7: builds RVO2-3D (/work/shared/peers/RVO2-3D, or $RVO2_3D) with the driver
# scripts/rvo2/sphere_ref.cc and writes the reference trajectories the Rust test
# `orca3d::tests::conformance_rvo2_sphere` compares against.
# Single-threaded, no -march=native and no FP contraction (no FMA), so every float operation
# is the plain IEEE-754 one Rust's f32 performs.
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
root="$(cd "$here/.." && pwd)"
rvo="${RVO2_3D:-/work/shared/peers/RVO2-3D}"
out="$root/core-nostd/src/orca3d/testdata/rvo2_sphere.txt"
tmp="$(mktemp -d)"
trap 'rm -rf "$tmp"' EXIT
g++ -std=c++11 -O2 -ffp-contract=off -fno-fast-math -I "$rvo/src" -I "$rvo/gen" \
    "$rvo"/src/*.cc "$here/rvo2/sphere_ref.cc" -o "$tmp/sphere_ref"
"$tmp/sphere_ref" > "$out"
echo "wrote $out ($(wc -c < "$out") bytes, $(($(wc -l < "$out") - 2)) steps)"
