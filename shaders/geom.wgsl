// Small vectors over the scalar `S` (host-sim/src/gpu/shaders.rs, GEOM): `swarm_core::geom`
// (core-nostd/src/geom.rs), function by function, generic over `S` as the Rust is: a kernel
// composes it after one scalar module (scalar_fx.wgsl or scalar_f32.wgsl). A `Vec2<S>` is a
// `vec2<S>`, a `Vec3<S>` a `vec3<S>`, a `Rect<S>` a `GeomRect`. For `S = Fx` every function
// gives the bits of its Rust original for every input (host-sim/src/gpu/tests/geom.rs).
//
// `direct` (geom.rs) is honoured through `S_DIRECT_LENGTH`: false for `Fx` (lengths and
// `normalized` are the scaled computations), true for f32 (√(x² + y²) in the normal range).
// `new` and `zero` are WGSL's constructors (`vec2<S>(x, y)`, `vec2<S>()`); an `Option` is a
// `GeomOptionVec2`/`GeomOptionVec3`; a `Result` of `check` is a bool (true for `Ok`). Not
// ported: `cast` (through f32 to another scalar).

// Option<Vec2<S>>: `value` is (0, 0) when `is_some` is false.
struct GeomOptionVec2 {
    is_some: bool,
    value: vec2<S>,
}

// Option<Vec3<S>>: `value` is (0, 0, 0) when `is_some` is false.
struct GeomOptionVec3 {
    is_some: bool,
    value: vec3<S>,
}

// Rect<S>: an axis-aligned rectangle [min, max].
struct GeomRect {
    min: vec2<S>,
    max: vec2<S>,
}

// direct (geom.rs): whether a vector of squared length `l2` has its length computed directly
// as √l2 (`S::DIRECT_LENGTH` and 1e-30 < l2 < 1e30); the callers compute `l2` only then.
fn geom_direct(l2: S) -> bool {
    return l2 > s_from_f32(1e-30f) && l2 < s_from_f32(1e30f);
}

// ---- Vec2 ----

// Vec2::from_f32, from the components' f32 bits.
fn geom_from_f32_bits(bits: vec2<u32>) -> vec2<S> {
    return vec2<S>(s_from_f32_bits(bits.x), s_from_f32_bits(bits.y));
}

// Vec2::dot: dot product.
fn geom_dot(a: vec2<S>, o: vec2<S>) -> S {
    return s_add(s_mul(a.x, o.x), s_mul(a.y, o.y));
}

// Vec2::cross: z component of the 3D cross product (positive when o is counter-clockwise of a).
fn geom_cross(a: vec2<S>, o: vec2<S>) -> S {
    return s_sub(s_mul(a.x, o.y), s_mul(a.y, o.x));
}

// Vec2::length_sq: squared length.
fn geom_length_sq(v: vec2<S>) -> S {
    return geom_dot(v, v);
}

// Vec2::length: √(x² + y²) where `direct`; else computed without squaring large components
// (no overflow below 32768 in fixed point).
fn geom_length(v: vec2<S>) -> S {
    if (S_DIRECT_LENGTH) {
        let l2 = geom_dot(v, v);
        if (geom_direct(l2)) {
            return s_sqrt(l2);
        }
    }
    let m = s_max(s_abs(v.x), s_abs(v.y));
    if (m == S_ZERO) {
        return S_ZERO;
    }
    // Scale by the larger component so the squares stay ≤ 2 (safe for fixed point).
    let a = s_div(v.x, m);
    let b = s_div(v.y, m);
    return s_mul(m, s_sqrt(s_add(s_mul(a, a), s_mul(b, b))));
}

// Vec2::normalized: the unit vector along v, or None for a zero vector.
fn geom_normalized(v: vec2<S>) -> GeomOptionVec2 {
    if (S_DIRECT_LENGTH) {
        let l2 = geom_dot(v, v);
        if (geom_direct(l2)) {
            let l = s_sqrt(l2);
            return GeomOptionVec2(true, vec2<S>(s_div(v.x, l), s_div(v.y, l)));
        }
    }
    // Scale by the largest component first: exact for fixed-point vectors of a few ulps, whose
    // length alone would be too coarse to divide by.
    let m = s_max(s_abs(v.x), s_abs(v.y));
    if (m == S_ZERO) {
        return GeomOptionVec2(false, vec2<S>());
    }
    let s = vec2<S>(s_div(v.x, m), s_div(v.y, m));
    let l = s_sqrt(geom_dot(s, s));
    return GeomOptionVec2(true, vec2<S>(s_div(s.x, l), s_div(s.y, l)));
}

// `v.normalized().unwrap_or(fallback)`.
fn geom_normalized_or(v: vec2<S>, fallback: vec2<S>) -> vec2<S> {
    let n = geom_normalized(v);
    return select(fallback, n.value, n.is_some);
}

// Vec2::perp: rotated counter-clockwise by 90°.
fn geom_perp(v: vec2<S>) -> vec2<S> {
    return vec2<S>(s_neg(v.y), v.x);
}

// Vec2::rotated: rotated counter-clockwise by `angle` radians.
fn geom_rotated(v: vec2<S>, angle: S) -> vec2<S> {
    let sc = s_sin_cos(angle);
    let s = sc.x;
    let c = sc.y;
    return vec2<S>(
        s_sub(s_mul(v.x, c), s_mul(v.y, s)),
        s_add(s_mul(v.x, s), s_mul(v.y, c)),
    );
}

// Vec2::from_angle: the unit vector at `angle` radians from the x axis.
fn geom_from_angle(angle: S) -> vec2<S> {
    let sc = s_sin_cos(angle);
    return vec2<S>(sc.y, sc.x);
}

// Vec2::check: whether both components are finite (always, for Fx).
fn geom_check(v: vec2<S>) -> bool {
    return s_is_finite(v.x) && s_is_finite(v.y);
}

// Vec2::to_f32, as the components' f32 bits.
fn geom_to_f32_bits(v: vec2<S>) -> vec2<u32> {
    return vec2<u32>(s_to_f32_bits(v.x), s_to_f32_bits(v.y));
}

// Add for Vec2.
fn geom_add(a: vec2<S>, o: vec2<S>) -> vec2<S> {
    return vec2<S>(s_add(a.x, o.x), s_add(a.y, o.y));
}

// Sub for Vec2.
fn geom_sub(a: vec2<S>, o: vec2<S>) -> vec2<S> {
    return vec2<S>(s_sub(a.x, o.x), s_sub(a.y, o.y));
}

// Neg for Vec2.
fn geom_neg(v: vec2<S>) -> vec2<S> {
    return vec2<S>(s_neg(v.x), s_neg(v.y));
}

// Mul<S> for Vec2: v · k.
fn geom_mul(v: vec2<S>, k: S) -> vec2<S> {
    return vec2<S>(s_mul(v.x, k), s_mul(v.y, k));
}

// ---- Vec3 ----

// Vec3::up: the up axis (0, 1, 0).
fn geom_vec3_up() -> vec3<S> {
    return vec3<S>(S_ZERO, S_ONE, S_ZERO);
}

// Vec3::from_f32, from the components' f32 bits.
fn geom_vec3_from_f32_bits(bits: vec3<u32>) -> vec3<S> {
    return vec3<S>(s_from_f32_bits(bits.x), s_from_f32_bits(bits.y), s_from_f32_bits(bits.z));
}

// Vec3::dot: dot product.
fn geom_vec3_dot(a: vec3<S>, o: vec3<S>) -> S {
    return s_add(s_add(s_mul(a.x, o.x), s_mul(a.y, o.y)), s_mul(a.z, o.z));
}

// Vec3::cross: cross product.
fn geom_vec3_cross(a: vec3<S>, o: vec3<S>) -> vec3<S> {
    return vec3<S>(
        s_sub(s_mul(a.y, o.z), s_mul(a.z, o.y)),
        s_sub(s_mul(a.z, o.x), s_mul(a.x, o.z)),
        s_sub(s_mul(a.x, o.y), s_mul(a.y, o.x)),
    );
}

// Vec3::length_sq: squared length.
fn geom_vec3_length_sq(v: vec3<S>) -> S {
    return geom_vec3_dot(v, v);
}

// Vec3::length: √(x² + y² + z²) where `direct`; else computed without squaring large
// components.
fn geom_vec3_length(v: vec3<S>) -> S {
    if (S_DIRECT_LENGTH) {
        let l2 = geom_vec3_dot(v, v);
        if (geom_direct(l2)) {
            return s_sqrt(l2);
        }
    }
    let m = s_max(s_max(s_abs(v.x), s_abs(v.y)), s_abs(v.z));
    if (m == S_ZERO) {
        return S_ZERO;
    }
    let a = s_div(v.x, m);
    let b = s_div(v.y, m);
    let c = s_div(v.z, m);
    return s_mul(m, s_sqrt(s_add(s_add(s_mul(a, a), s_mul(b, b)), s_mul(c, c))));
}

// Vec3::normalized: the unit vector along v, or None for a zero vector.
fn geom_vec3_normalized(v: vec3<S>) -> GeomOptionVec3 {
    if (S_DIRECT_LENGTH) {
        let l2 = geom_vec3_dot(v, v);
        if (geom_direct(l2)) {
            let l = s_sqrt(l2);
            return GeomOptionVec3(true, vec3<S>(s_div(v.x, l), s_div(v.y, l), s_div(v.z, l)));
        }
    }
    // Scale by the largest component first (see `geom_normalized`).
    let m = s_max(s_max(s_abs(v.x), s_abs(v.y)), s_abs(v.z));
    if (m == S_ZERO) {
        return GeomOptionVec3(false, vec3<S>());
    }
    let s = vec3<S>(s_div(v.x, m), s_div(v.y, m), s_div(v.z, m));
    let l = s_sqrt(geom_vec3_dot(s, s));
    return GeomOptionVec3(true, vec3<S>(s_div(s.x, l), s_div(s.y, l), s_div(s.z, l)));
}

// Vec3::check: whether every component is finite (always, for Fx).
fn geom_vec3_check(v: vec3<S>) -> bool {
    return s_is_finite(v.x) && s_is_finite(v.y) && s_is_finite(v.z);
}

// Vec3::to_f32, as the components' f32 bits.
fn geom_vec3_to_f32_bits(v: vec3<S>) -> vec3<u32> {
    return vec3<u32>(s_to_f32_bits(v.x), s_to_f32_bits(v.y), s_to_f32_bits(v.z));
}

// Add for Vec3.
fn geom_vec3_add(a: vec3<S>, o: vec3<S>) -> vec3<S> {
    return vec3<S>(s_add(a.x, o.x), s_add(a.y, o.y), s_add(a.z, o.z));
}

// Sub for Vec3.
fn geom_vec3_sub(a: vec3<S>, o: vec3<S>) -> vec3<S> {
    return vec3<S>(s_sub(a.x, o.x), s_sub(a.y, o.y), s_sub(a.z, o.z));
}

// Neg for Vec3.
fn geom_vec3_neg(v: vec3<S>) -> vec3<S> {
    return vec3<S>(s_neg(v.x), s_neg(v.y), s_neg(v.z));
}

// Mul<S> for Vec3: v · k.
fn geom_vec3_mul(v: vec3<S>, k: S) -> vec3<S> {
    return vec3<S>(s_mul(v.x, k), s_mul(v.y, k), s_mul(v.z, k));
}

// ---- Rect ----

// Rect::contains: whether p lies inside (borders included).
fn geom_rect_contains(r: GeomRect, p: vec2<S>) -> bool {
    return p.x >= r.min.x && p.x <= r.max.x && p.y >= r.min.y && p.y <= r.max.y;
}

// Rect::clamp: p moved to the nearest point inside.
fn geom_rect_clamp(r: GeomRect, p: vec2<S>) -> vec2<S> {
    return vec2<S>(s_clamp_to(p.x, r.min.x, r.max.x), s_clamp_to(p.y, r.min.y, r.max.y));
}

// Rect::check: Ok (true) unless a corner is not finite or min < max fails on an axis.
fn geom_rect_check(r: GeomRect) -> bool {
    return geom_check(r.min) && geom_check(r.max) && r.min.x < r.max.x && r.min.y < r.max.y;
}
