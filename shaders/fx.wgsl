// I16F16 fixed point (host-sim/src/gpu/shaders.rs, FX): the arithmetic of `swarm_core::Fx`
// (core-nostd/src/scalar/fx.rs) and the provided methods of `Scalar` it uses
// (core-nostd/src/scalar/mod.rs), one function per Rust function, in the order of fx.rs.
//
// An `Fx` is its raw bits, an `i32` (value = bits / 65536). Every function gives the bits of its
// Rust original for every input (host-sim/src/gpu/tests/fx.rs checks each on the GPU against the
// Rust function, edge cases and a few hundred thousand pseudo-random inputs).
//
// Integers only, never f32: GPU drivers may fuse or reorder float operations. WGSL semantics
// this file relies on, and works around:
//
// * `+`, `-`, `*` of i32 and u32 wrap (two's complement), `-FX_MIN` is `FX_MIN`: the saturating
//   operations test before they compute, as `i32::saturating_*` behaves.
// * `>>` of an i32 is arithmetic (sign-extending), of a u32 logical.
// * a shift amount must be below 32 (a run-time amount is taken modulo 32): the 64-bit shifts
//   branch on it.
// * `/` and `%` by zero, and `FX_MIN / -1`, give values Rust would not (or panics): every
//   division here has a divisor that is not zero, `u32` operands or (`fx_rem_euclid`) a
//   positive `i32` divisor, as in the Rust code.
// * there is no 64-bit integer: an `i64`/`u64` of fx.rs is a `vec2<u32>` (low word, high word),
//   two's complement for `i64` (the `fx_u64_*` and `fx_i64_*` helpers).
//
// And one of the drivers: lavapipe's compile time grows faster than linearly with the number of
// loops in a kernel (every call is inlined; 20 small loops compile in about a second, 80 in
// 47 s), so division and square root, used dozens of times by a controller, have no loop whose
// count the compiler cannot see (fx_div_q16, fx_isqrt_q16: fixed counts, unrolled).

// ---- 64-bit integers as two words (the i64/u64 arithmetic of fx.rs) ----

// `v as u64` for a u32: zero-extended.
fn fx_u64_from_u32(v: u32) -> vec2<u32> {
    return vec2<u32>(v, 0u);
}

// `v as i64` for an i32: sign-extended.
fn fx_i64_from_i32(v: i32) -> vec2<u32> {
    return vec2<u32>(bitcast<u32>(v), bitcast<u32>(v >> 31u));
}

// `a.wrapping_add(b)` (u64 and i64 alike).
fn fx_u64_add(a: vec2<u32>, b: vec2<u32>) -> vec2<u32> {
    let lo = a.x + b.x;
    let carry = select(0u, 1u, lo < a.x);
    return vec2<u32>(lo, a.y + b.y + carry);
}

// `a.wrapping_sub(b)` (u64 and i64 alike).
fn fx_u64_sub(a: vec2<u32>, b: vec2<u32>) -> vec2<u32> {
    let borrow = select(0u, 1u, a.x < b.x);
    return vec2<u32>(a.x - b.x, a.y - b.y - borrow);
}

// `-a` of an i64 (wrapping).
fn fx_i64_neg(a: vec2<u32>) -> vec2<u32> {
    return fx_u64_sub(vec2<u32>(0u, 0u), a);
}

// `a < b` of two u64.
fn fx_u64_lt(a: vec2<u32>, b: vec2<u32>) -> bool {
    return a.y < b.y || (a.y == b.y && a.x < b.x);
}

// `a << k` (u64 and i64 alike), `k < 64`.
fn fx_u64_shl(a: vec2<u32>, k: u32) -> vec2<u32> {
    if (k == 0u) {
        return a;
    }
    if (k < 32u) {
        return vec2<u32>(a.x << k, (a.y << k) | (a.x >> (32u - k)));
    }
    return vec2<u32>(0u, a.x << (k - 32u));
}

// `a >> k` of a u64 (logical), `k < 64`.
fn fx_u64_shr(a: vec2<u32>, k: u32) -> vec2<u32> {
    if (k == 0u) {
        return a;
    }
    if (k < 32u) {
        return vec2<u32>((a.x >> k) | (a.y << (32u - k)), a.y >> k);
    }
    return vec2<u32>(a.y >> (k - 32u), 0u);
}

// `a >> k` of an i64 (arithmetic), `k < 64`.
fn fx_i64_shr(a: vec2<u32>, k: u32) -> vec2<u32> {
    let hi = bitcast<i32>(a.y);
    if (k == 0u) {
        return a;
    }
    if (k < 32u) {
        return vec2<u32>((a.x >> k) | (a.y << (32u - k)), bitcast<u32>(hi >> k));
    }
    return vec2<u32>(bitcast<u32>(hi >> (k - 32u)), bitcast<u32>(hi >> 31u));
}

// `a as u64 * b as u64`: the four products of the 16-bit halves (each below 2^32), added with
// their carries.
fn fx_u64_mul(a: u32, b: u32) -> vec2<u32> {
    let al = a & 0xffffu;
    let ah = a >> 16u;
    let bl = b & 0xffffu;
    let bh = b >> 16u;
    let ll = al * bl;
    let lh = al * bh;
    let hl = ah * bl;
    let hh = ah * bh;
    // Bits 16..47 of the sum: below 3 · 2^16, no overflow.
    let mid = (ll >> 16u) + (lh & 0xffffu) + (hl & 0xffffu);
    return vec2<u32>((mid << 16u) | (ll & 0xffffu), hh + (lh >> 16u) + (hl >> 16u) + (mid >> 16u));
}

// `a as i64 * b as i64`: the unsigned product of the bits, less 2^32 · b where a < 0 and
// 2^32 · a where b < 0 (modulo 2^64).
fn fx_i64_mul(a: i32, b: i32) -> vec2<u32> {
    let p = fx_u64_mul(bitcast<u32>(a), bitcast<u32>(b));
    let fa = select(0u, bitcast<u32>(b), a < 0);
    let fb = select(0u, bitcast<u32>(a), b < 0);
    return vec2<u32>(p.x, p.y - fa - fb);
}

// `i32::unsigned_abs`: |a| as u32 (2^31 for FX_MIN).
fn fx_unsigned_abs(a: i32) -> u32 {
    return select(bitcast<u32>(a), 0u - bitcast<u32>(a), a < 0);
}

// `i32::rem_euclid(a, m)` for `m > 0` (WGSL's `%` truncates toward zero, as Rust's `%` does).
fn fx_rem_euclid(a: i32, m: i32) -> i32 {
    let r = a % m;
    return select(r, r + m, r < 0);
}

// ---- Fx ----

// Fx::MAX, the largest value, 32767.99998.
const FX_MAX: i32 = 2147483647;
// Fx::MIN, the smallest value, -32768.
const FX_MIN: i32 = -2147483648;
// Scalar::ZERO, ONE, EPS.
const FX_ZERO: i32 = 0;
const FX_ONE: i32 = 65536;
const FX_EPS: i32 = 1;
// PI_RAW, TAU_RAW, HALF_PI_RAW of fx.rs (also `pi::<Fx>()`, `Fx::from_f32(TAU)`,
// `Fx::from_f32(FRAC_PI_2)`).
const FX_PI_RAW: i32 = 205887;
const FX_TAU_RAW: i32 = 411775;
const FX_HALF_PI_RAW: i32 = 102944;
// `scalar::pi::<Fx>()`: `Fx::from_f32(core::f32::consts::PI)`.
const FX_PI: i32 = 205887;
// `Fx::from_f32(core::f32::consts::PI / 180.0)`, the factor of `scalar::deg`.
const FX_DEG: i32 = 1144;

// Fx::sat: an i64 saturated into the i32 range.
fn fx_sat(v: vec2<u32>) -> i32 {
    let hi = bitcast<i32>(v.y);
    if (hi > 0 || (hi == 0 && v.x > 0x7fffffffu)) {
        return FX_MAX;
    } else if (hi < -1 || (hi == -1 && v.x < 0x80000000u)) {
        return FX_MIN;
    } else {
        return bitcast<i32>(v.x);
    }
}

// Fx::sin_quadrant: sine on [0, π/2] (raw units), via the polynomial in y = 2x/π.
fn fx_sin_quadrant(x: i32) -> i32 {
    let y = fx_mul(x, 41722);
    let y2 = fx_mul(y, y);
    var p: i32 = 11;
    p = fx_add(-307, fx_mul(y2, p));
    p = fx_add(5223, fx_mul(y2, p));
    p = fx_add(-42334, fx_mul(y2, p));
    p = fx_add(FX_HALF_PI_RAW, fx_mul(y2, p));
    return fx_min(fx_mul(y, p), FX_ONE);
}

// Fx::sin_reduced: sine of a reduced angle in [0, 2π) (raw units).
fn fx_sin_reduced(a_in: i32) -> i32 {
    var a = a_in;
    var neg = false;
    if (a >= FX_PI_RAW) {
        a = a - FX_PI_RAW;
        neg = true;
    }
    if (a > FX_HALF_PI_RAW) {
        a = FX_PI_RAW - a;
    }
    let s = fx_sin_quadrant(a);
    if (neg) {
        return fx_neg(s);
    }
    return s;
}

// isqrt (fx.rs): integer square root (floor) of a u64 by the digit-by-digit method.
fn fx_isqrt(n: vec2<u32>) -> vec2<u32> {
    var x = n;
    var r = vec2<u32>(0u, 0u);
    var bit = vec2<u32>(0u, 1u << 30u); // 1 << 62
    while (fx_u64_lt(n, bit)) {
        bit = fx_u64_shr(bit, 2u);
    }
    while (bit.x != 0u || bit.y != 0u) {
        let rb = fx_u64_add(r, bit);
        if (!fx_u64_lt(x, rb)) {
            x = fx_u64_sub(x, rb);
            r = fx_u64_add(fx_u64_shr(r, 1u), bit);
        } else {
            r = fx_u64_shr(r, 1u);
        }
        bit = fx_u64_shr(bit, 2u);
    }
    return r;
}

// Add for Fx: `i32::saturating_add`.
fn fx_add(a: i32, b: i32) -> i32 {
    if (b > 0 && a > FX_MAX - b) {
        return FX_MAX;
    }
    if (b < 0 && a < FX_MIN - b) {
        return FX_MIN;
    }
    return a + b;
}

// Sub for Fx: `i32::saturating_sub`.
fn fx_sub(a: i32, b: i32) -> i32 {
    if (b < 0 && a > FX_MAX + b) {
        return FX_MAX;
    }
    if (b > 0 && a < FX_MIN + b) {
        return FX_MIN;
    }
    return a - b;
}

// Mul for Fx: sat((a·b + 2^15) >> 16), the 64-bit product rounded to nearest (ties up).
fn fx_mul(a: i32, b: i32) -> i32 {
    let p = fx_i64_mul(a, b);
    return fx_sat(fx_i64_shr(fx_u64_add(p, fx_u64_from_u32(1u << 15u)), 16u));
}

// Div for Fx: sat(trunc((a << 16) / b)); x / 0 is ±MAX by the sign of x, 0 / 0 = 0.
fn fx_div(a: i32, b: i32) -> i32 {
    if (b == 0) {
        if (a == 0) {
            return FX_ZERO;
        } else if (a > 0) {
            return FX_MAX;
        } else {
            return FX_MIN;
        }
    }
    let q = fx_div_q16(fx_unsigned_abs(a), fx_unsigned_abs(b));
    if ((a < 0) != (b < 0)) {
        return fx_sat(fx_i64_neg(q));
    }
    return fx_sat(q);
}

// div_q16 (fx.rs): `(n << 16) / d`, truncated (`d > 0`, `n ≤ 2^31`, `d ≤ 2^31`): the integer part
// with the 32-bit divide, then the 16 fraction bits by restoring division, one bit a step (the
// remainder `r < d ≤ 2^31`, so `r << 1` fits in 32 bits): the same quotient as div_q16_words'
// digits. A loop of a fixed 16 steps, which compilers unroll: lavapipe's compile time grows
// faster than linearly with the number of loops in a kernel (a loop per division made the bee
// controller's kernel take minutes to compile).
fn fx_div_q16(n: u32, d: u32) -> vec2<u32> {
    let q = n / d;
    var r = n - q * d;
    var f = 0u;
    for (var i = 0u; i < 16u; i = i + 1u) {
        r = r << 1u;
        let bit = r >= d;
        r = select(r, r - d, bit);
        f = (f << 1u) | select(0u, 1u, bit);
    }
    return vec2<u32>((q << 16u) | f, q >> 16u);
}

// Neg for Fx: `i32::saturating_neg` (-MIN = MAX).
fn fx_neg(a: i32) -> i32 {
    if (a == FX_MIN) {
        return FX_MAX;
    }
    return -a;
}

// Scalar::abs for Fx: `i32::saturating_abs` (|MIN| = MAX).
fn fx_abs(a: i32) -> i32 {
    if (a == FX_MIN) {
        return FX_MAX;
    }
    if (a < 0) {
        return -a;
    }
    return a;
}

// Scalar::from_f32 for Fx (`i16f16_bits` of scalar/mod.rs), from the f32's bits: `v · 2^16`
// rounded to the nearest integer, ties to even, saturating; NaN gives 0. The Rust function
// rounds with f32 arithmetic; here the same rounding is done on the integer significand.
fn fx_from_f32_bits(v: u32) -> i32 {
    let neg = (v >> 31u) != 0u;
    let e = (v >> 23u) & 0xffu;
    let f = v & 0x7fffffu;
    if (e == 0xffu) {
        if (f != 0u) {
            return 0; // NaN
        }
        return select(FX_MAX, FX_MIN, neg); // ±inf
    }
    // |v| · 2^16 = m · 2^s (a subnormal has no implicit bit and the exponent of e = 1).
    var m = f | 0x800000u;
    var s = i32(e) - 134;
    if (e == 0u) {
        m = f;
        s = -133;
    }
    var mag: u32;
    if (s >= 8) {
        // m ≥ 2^23: |v| · 2^16 ≥ 2^31.
        return select(FX_MAX, FX_MIN, neg);
    } else if (s >= 0) {
        mag = m << u32(s); // below 2^31
    } else if (s < -24) {
        mag = 0u; // m < 2^24: below 1/2
    } else {
        let k = u32(-s);
        mag = m >> k;
        let rest = m & ((1u << k) - 1u);
        let half = 1u << (k - 1u);
        if (rest > half || (rest == half && (mag & 1u) == 1u)) {
            mag = mag + 1u;
        }
    }
    let r = bitcast<i32>(mag);
    return select(r, -r, neg);
}

// Scalar::to_f32 for Fx (`I16F16::to_num::<f32>`), as the f32's bits: the value rounded to 24
// significant bits, to the nearest, ties to even (exact below 256.0).
fn fx_to_f32_bits(a: i32) -> u32 {
    if (a == 0) {
        return 0u;
    }
    let sign = select(0u, 0x80000000u, a < 0);
    var m = fx_unsigned_abs(a);
    // The top bit: m in [2^p, 2^(p + 1)).
    var p = 31u - countLeadingZeros(m);
    if (p > 23u) {
        let k = p - 23u;
        let rest = m & ((1u << k) - 1u);
        let half = 1u << (k - 1u);
        m = m >> k;
        if (rest > half || (rest == half && (m & 1u) == 1u)) {
            m = m + 1u;
            if (m == 0x1000000u) {
                m = m >> 1u;
                p = p + 1u;
            }
        }
    } else {
        m = m << (23u - p);
    }
    // value = m · 2^(p - 23 - 16), m in [2^23, 2^24): exponent p - 16, biased p + 111.
    return sign | ((p + 111u) << 23u) | (m & 0x7fffffu);
}

// Scalar::from_i32 for Fx: sat(v << 16).
fn fx_from_i32(v: i32) -> i32 {
    return fx_sat(fx_u64_shl(fx_i64_from_i32(v), 16u));
}

// Scalar::floor_i32 for Fx: the bits shifted right (arithmetic).
fn fx_floor_i32(a: i32) -> i32 {
    return a >> 16u;
}

// Scalar::is_finite for Fx: always true.
fn fx_is_finite(a: i32) -> bool {
    return true;
}

// Scalar::unit_open for Fx: 15 random bits as an odd 16-bit fraction, (2k + 1) / 2^16, strictly
// inside (0, 1).
fn fx_unit_open(bits: u32) -> i32 {
    return bitcast<i32>(((bits >> 17u) << 1u) | 1u);
}

// Scalar::sqrt for Fx: the floor of the integer square root of `a << 16`; 0 for a ≤ 0.
fn fx_sqrt(a: i32) -> i32 {
    let r = a;
    if (r <= 0) {
        return FX_ZERO;
    }
    // `isqrt(..) as i32` (the root is below 2^24).
    return bitcast<i32>(fx_isqrt_q16(bitcast<u32>(r)));
}

// isqrt (fx.rs) of `a << 16` for a u32 `a`: the same digit-by-digit method as fx_isqrt, on the
// 24 pairs of bits of `a << 16` from the top (the 16 of `a`, then 8 zero pairs; leading zero
// pairs leave the root at 0, so starting at the top equals isqrt's skipping them), the partial
// root and remainder in 32 bits (the remainder stays at most twice the root, below 2^25). Loops
// of a fixed 16 and 8 steps, which compilers unroll (see fx_div_q16).
fn fx_isqrt_q16(a: u32) -> u32 {
    // (remainder, root)
    var s = vec2<u32>(0u, 0u);
    for (var i = 0u; i < 16u; i = i + 1u) {
        s = fx_isqrt_digit(s, (a >> (30u - 2u * i)) & 3u);
    }
    for (var i = 0u; i < 8u; i = i + 1u) {
        s = fx_isqrt_digit(s, 0u);
    }
    return s.y;
}

// One digit of fx_isqrt_q16: the next pair of bits into the remainder, and the root's next bit
// (1 if the remainder holds 4·root + 1).
fn fx_isqrt_digit(s: vec2<u32>, pair: u32) -> vec2<u32> {
    let rem = (s.x << 2u) | pair;
    let trial = (s.y << 2u) | 1u;
    let one = rem >= trial;
    return vec2<u32>(select(rem, rem - trial, one), (s.y << 1u) | select(0u, 1u, one));
}

// Scalar::sin for Fx.
fn fx_sin(a: i32) -> i32 {
    return fx_sin_reduced(fx_rem_euclid(a, FX_TAU_RAW));
}

// Scalar::cos for Fx.
fn fx_cos(a_in: i32) -> i32 {
    let a = fx_rem_euclid(a_in, FX_TAU_RAW) + FX_HALF_PI_RAW;
    if (a >= FX_TAU_RAW) {
        return fx_sin_reduced(a - FX_TAU_RAW);
    }
    return fx_sin_reduced(a);
}

// Scalar::sin_cos (provided): (sin, cos).
fn fx_sin_cos(a: i32) -> vec2<i32> {
    return vec2<i32>(fx_sin(a), fx_cos(a));
}

// Scalar::atan2 for Fx: `y.atan2(x)`, in (-π, π]; atan2(0, 0) = 0.
fn fx_atan2(y: i32, x: i32) -> i32 {
    if (x == FX_ZERO && y == FX_ZERO) {
        return FX_ZERO;
    }
    let ax = fx_abs(x);
    let ay = fx_abs(y);
    let swap = ay > ax;
    var z: i32;
    if (swap) {
        z = fx_div(ax, ay);
    } else {
        z = fx_div(ay, ax);
    }
    let z2 = fx_mul(z, z);
    var p: i32 = 1365;
    p = fx_add(-5579, fx_mul(z2, p));
    p = fx_add(11806, fx_mul(z2, p));
    p = fx_add(-21647, fx_mul(z2, p));
    p = fx_add(65527, fx_mul(z2, p));
    var r = fx_mul(z, p);
    if (swap) {
        r = fx_sub(FX_HALF_PI_RAW, r);
    }
    if (x < FX_ZERO) {
        r = fx_sub(FX_PI_RAW, r);
    }
    if (y < FX_ZERO) {
        return fx_neg(r);
    }
    return r;
}

// Scalar::exp for Fx: e^x = 2^k · e^r; MAX above ln(32768), 0 below ln(2^-17).
fn fx_exp(a: i32) -> i32 {
    let raw = a;
    if (raw > 681391) {
        return FX_MAX;
    }
    if (raw < -772244) {
        return FX_ZERO;
    }
    // k = round(x / ln 2), r = x - k ln 2.
    let k = fx_floor_i32(fx_add(fx_mul(a, 94548), 1 << 15u));
    let r = fx_sub(a, fx_mul(fx_from_i32(k), 45426));
    var p: i32 = 91;
    p = fx_add(546, fx_mul(r, p));
    p = fx_add(2731, fx_mul(r, p));
    p = fx_add(10923, fx_mul(r, p));
    p = fx_add(32768, fx_mul(r, p));
    p = fx_add(FX_ONE, fx_mul(r, p));
    p = fx_add(FX_ONE, fx_mul(r, p));
    let bits = fx_i64_from_i32(p);
    if (k >= 0) {
        return fx_sat(fx_u64_shl(bits, u32(min(k, 31))));
    } else {
        let s = u32(min(-k, 40));
        return fx_sat(fx_i64_shr(fx_u64_add(bits, fx_u64_shl(fx_u64_from_u32(1u), s - 1u)), s));
    }
}

// ---- the provided methods of Scalar (scalar/mod.rs) ----

// Scalar::min: the smaller of two values.
fn fx_min(a: i32, o: i32) -> i32 {
    if (o < a) {
        return o;
    }
    return a;
}

// Scalar::max: the larger of two values.
fn fx_max(a: i32, o: i32) -> i32 {
    if (o > a) {
        return o;
    }
    return a;
}

// Scalar::clamp_to: `a` limited to [lo, hi] (never fails, even if lo > hi).
fn fx_clamp_to(a: i32, lo: i32, hi: i32) -> i32 {
    return fx_min(fx_max(a, lo), hi);
}

// Scalar::signum: -1, 0 or +1.
fn fx_signum(a: i32) -> i32 {
    if (a > FX_ZERO) {
        return FX_ONE;
    } else if (a < FX_ZERO) {
        return fx_neg(FX_ONE);
    } else {
        return FX_ZERO;
    }
}

// Scalar::powi: `a^n` by repeated multiplication (`n` is a u8 in Rust: 0..=255).
fn fx_powi(a: i32, n: u32) -> i32 {
    var acc = FX_ONE;
    for (var i = 0u; i < n; i = i + 1u) {
        acc = fx_mul(acc, a);
    }
    return acc;
}

// scalar::deg: degrees to radians.
fn fx_deg(d: i32) -> i32 {
    return fx_mul(d, FX_DEG);
}
