// Small vectors over Fx (host-sim/src/gpu/shaders.rs, GEOM): `swarm_core::geom`
// (core-nostd/src/geom.rs) for `S = Fx`, function by function, on the raw bits: a `Vec2<Fx>` is
// a `vec2<i32>`, a `Vec3<Fx>` a `vec3<i32>`, a `Rect<Fx>` a `GeomRect`. Every function gives
// the bits of its Rust original for every input (host-sim/src/gpu/tests/geom.rs); uses fx.wgsl.
//
// `Fx::DIRECT_LENGTH` is false, so `direct` (geom.rs) is always `None` and `length` and
// `normalized` are the scaled computations. `new` and `zero` are WGSL's constructors
// (`vec2<i32>(x, y)`, `vec2<i32>()`); an `Option` is a `GeomOptionVec2`/`GeomOptionVec3`; a
// `Result` of `check` is a bool (true for `Ok`). Not ported: `cast` (through f32 to another
// scalar: for f32 it is `to_f32`).

// Option<Vec2<Fx>>: `value` is (0, 0) when `is_some` is false.
struct GeomOptionVec2 {
    is_some: bool,
    value: vec2<i32>,
}

// Option<Vec3<Fx>>: `value` is (0, 0, 0) when `is_some` is false.
struct GeomOptionVec3 {
    is_some: bool,
    value: vec3<i32>,
}

// Rect<Fx>: an axis-aligned rectangle [min, max].
struct GeomRect {
    min: vec2<i32>,
    max: vec2<i32>,
}

// ---- Vec2 ----

// Vec2::from_f32, from the components' f32 bits.
fn geom_from_f32_bits(bits: vec2<u32>) -> vec2<i32> {
    return vec2<i32>(fx_from_f32_bits(bits.x), fx_from_f32_bits(bits.y));
}

// Vec2::dot: dot product.
fn geom_dot(a: vec2<i32>, o: vec2<i32>) -> i32 {
    return fx_add(fx_mul(a.x, o.x), fx_mul(a.y, o.y));
}

// Vec2::cross: z component of the 3D cross product (positive when o is counter-clockwise of a).
fn geom_cross(a: vec2<i32>, o: vec2<i32>) -> i32 {
    return fx_sub(fx_mul(a.x, o.y), fx_mul(a.y, o.x));
}

// Vec2::length_sq: squared length.
fn geom_length_sq(v: vec2<i32>) -> i32 {
    return geom_dot(v, v);
}

// Vec2::length: computed without squaring large components (no overflow below 32768).
fn geom_length(v: vec2<i32>) -> i32 {
    let m = fx_max(fx_abs(v.x), fx_abs(v.y));
    if (m == FX_ZERO) {
        return FX_ZERO;
    }
    // Scale by the larger component so the squares stay ≤ 2 (safe for fixed point).
    let a = fx_div(v.x, m);
    let b = fx_div(v.y, m);
    return fx_mul(m, fx_sqrt(fx_add(fx_mul(a, a), fx_mul(b, b))));
}

// Vec2::normalized: the unit vector along v, or None for a zero vector.
fn geom_normalized(v: vec2<i32>) -> GeomOptionVec2 {
    // Scale by the largest component first: exact for fixed-point vectors of a few ulps, whose
    // length alone would be too coarse to divide by.
    let m = fx_max(fx_abs(v.x), fx_abs(v.y));
    if (m == FX_ZERO) {
        return GeomOptionVec2(false, vec2<i32>());
    }
    let s = vec2<i32>(fx_div(v.x, m), fx_div(v.y, m));
    let l = fx_sqrt(geom_dot(s, s));
    return GeomOptionVec2(true, vec2<i32>(fx_div(s.x, l), fx_div(s.y, l)));
}

// Vec2::perp: rotated counter-clockwise by 90°.
fn geom_perp(v: vec2<i32>) -> vec2<i32> {
    return vec2<i32>(fx_neg(v.y), v.x);
}

// Vec2::rotated: rotated counter-clockwise by `angle` radians.
fn geom_rotated(v: vec2<i32>, angle: i32) -> vec2<i32> {
    let sc = fx_sin_cos(angle);
    let s = sc.x;
    let c = sc.y;
    return vec2<i32>(
        fx_sub(fx_mul(v.x, c), fx_mul(v.y, s)),
        fx_add(fx_mul(v.x, s), fx_mul(v.y, c)),
    );
}

// Vec2::from_angle: the unit vector at `angle` radians from the x axis.
fn geom_from_angle(angle: i32) -> vec2<i32> {
    let sc = fx_sin_cos(angle);
    return vec2<i32>(sc.y, sc.x);
}

// Vec2::check: whether both components are finite (always, for Fx).
fn geom_check(v: vec2<i32>) -> bool {
    return fx_is_finite(v.x) && fx_is_finite(v.y);
}

// Vec2::to_f32, as the components' f32 bits.
fn geom_to_f32_bits(v: vec2<i32>) -> vec2<u32> {
    return vec2<u32>(fx_to_f32_bits(v.x), fx_to_f32_bits(v.y));
}

// Add for Vec2.
fn geom_add(a: vec2<i32>, o: vec2<i32>) -> vec2<i32> {
    return vec2<i32>(fx_add(a.x, o.x), fx_add(a.y, o.y));
}

// Sub for Vec2.
fn geom_sub(a: vec2<i32>, o: vec2<i32>) -> vec2<i32> {
    return vec2<i32>(fx_sub(a.x, o.x), fx_sub(a.y, o.y));
}

// Neg for Vec2.
fn geom_neg(v: vec2<i32>) -> vec2<i32> {
    return vec2<i32>(fx_neg(v.x), fx_neg(v.y));
}

// Mul<S> for Vec2: v · k.
fn geom_mul(v: vec2<i32>, k: i32) -> vec2<i32> {
    return vec2<i32>(fx_mul(v.x, k), fx_mul(v.y, k));
}

// ---- Vec3 ----

// Vec3::up: the up axis (0, 1, 0).
fn geom_vec3_up() -> vec3<i32> {
    return vec3<i32>(FX_ZERO, FX_ONE, FX_ZERO);
}

// Vec3::from_f32, from the components' f32 bits.
fn geom_vec3_from_f32_bits(bits: vec3<u32>) -> vec3<i32> {
    return vec3<i32>(fx_from_f32_bits(bits.x), fx_from_f32_bits(bits.y), fx_from_f32_bits(bits.z));
}

// Vec3::dot: dot product.
fn geom_vec3_dot(a: vec3<i32>, o: vec3<i32>) -> i32 {
    return fx_add(fx_add(fx_mul(a.x, o.x), fx_mul(a.y, o.y)), fx_mul(a.z, o.z));
}

// Vec3::cross: cross product.
fn geom_vec3_cross(a: vec3<i32>, o: vec3<i32>) -> vec3<i32> {
    return vec3<i32>(
        fx_sub(fx_mul(a.y, o.z), fx_mul(a.z, o.y)),
        fx_sub(fx_mul(a.z, o.x), fx_mul(a.x, o.z)),
        fx_sub(fx_mul(a.x, o.y), fx_mul(a.y, o.x)),
    );
}

// Vec3::length_sq: squared length.
fn geom_vec3_length_sq(v: vec3<i32>) -> i32 {
    return geom_vec3_dot(v, v);
}

// Vec3::length: computed without squaring large components.
fn geom_vec3_length(v: vec3<i32>) -> i32 {
    let m = fx_max(fx_max(fx_abs(v.x), fx_abs(v.y)), fx_abs(v.z));
    if (m == FX_ZERO) {
        return FX_ZERO;
    }
    let a = fx_div(v.x, m);
    let b = fx_div(v.y, m);
    let c = fx_div(v.z, m);
    return fx_mul(m, fx_sqrt(fx_add(fx_add(fx_mul(a, a), fx_mul(b, b)), fx_mul(c, c))));
}

// Vec3::normalized: the unit vector along v, or None for a zero vector.
fn geom_vec3_normalized(v: vec3<i32>) -> GeomOptionVec3 {
    // Scale by the largest component first (see `geom_normalized`).
    let m = fx_max(fx_max(fx_abs(v.x), fx_abs(v.y)), fx_abs(v.z));
    if (m == FX_ZERO) {
        return GeomOptionVec3(false, vec3<i32>());
    }
    let s = vec3<i32>(fx_div(v.x, m), fx_div(v.y, m), fx_div(v.z, m));
    let l = fx_sqrt(geom_vec3_dot(s, s));
    return GeomOptionVec3(true, vec3<i32>(fx_div(s.x, l), fx_div(s.y, l), fx_div(s.z, l)));
}

// Vec3::check: whether every component is finite (always, for Fx).
fn geom_vec3_check(v: vec3<i32>) -> bool {
    return fx_is_finite(v.x) && fx_is_finite(v.y) && fx_is_finite(v.z);
}

// Vec3::to_f32, as the components' f32 bits.
fn geom_vec3_to_f32_bits(v: vec3<i32>) -> vec3<u32> {
    return vec3<u32>(fx_to_f32_bits(v.x), fx_to_f32_bits(v.y), fx_to_f32_bits(v.z));
}

// Add for Vec3.
fn geom_vec3_add(a: vec3<i32>, o: vec3<i32>) -> vec3<i32> {
    return vec3<i32>(fx_add(a.x, o.x), fx_add(a.y, o.y), fx_add(a.z, o.z));
}

// Sub for Vec3.
fn geom_vec3_sub(a: vec3<i32>, o: vec3<i32>) -> vec3<i32> {
    return vec3<i32>(fx_sub(a.x, o.x), fx_sub(a.y, o.y), fx_sub(a.z, o.z));
}

// Neg for Vec3.
fn geom_vec3_neg(v: vec3<i32>) -> vec3<i32> {
    return vec3<i32>(fx_neg(v.x), fx_neg(v.y), fx_neg(v.z));
}

// Mul<S> for Vec3: v · k.
fn geom_vec3_mul(v: vec3<i32>, k: i32) -> vec3<i32> {
    return vec3<i32>(fx_mul(v.x, k), fx_mul(v.y, k), fx_mul(v.z, k));
}

// ---- Rect ----

// Rect::contains: whether p lies inside (borders included).
fn geom_rect_contains(r: GeomRect, p: vec2<i32>) -> bool {
    return p.x >= r.min.x && p.x <= r.max.x && p.y >= r.min.y && p.y <= r.max.y;
}

// Rect::clamp: p moved to the nearest point inside.
fn geom_rect_clamp(r: GeomRect, p: vec2<i32>) -> vec2<i32> {
    return vec2<i32>(fx_clamp_to(p.x, r.min.x, r.max.x), fx_clamp_to(p.y, r.min.y, r.max.y));
}

// Rect::check: Ok (true) unless a corner is not finite or min < max fails on an axis.
fn geom_rect_check(r: GeomRect) -> bool {
    return geom_check(r.min) && geom_check(r.max) && r.min.x < r.max.x && r.min.y < r.max.y;
}
