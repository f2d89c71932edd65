// 3D Perlin noise (host-sim/src/gpu/shaders.rs, BEE_PERLIN): `swarm_core::bee::perlin`
// (core-nostd/src/bee/perlin.rs), the Per_k of chen eq. 8, over the scalar `S`: Ken Perlin's
// "improved noise" (2002) with his reference permutation table, the 12 cube-edge gradients and
// the quintic fade, returning the value together with its analytic gradient (eq. 9 needs
// derivatives). Self-contained (geom.wgsl only): the curl noise of the bees (bee_curl.wgsl) and
// any other model's noise use it.
//
// The lattice hashing is integer-only (`& 255` wrapping, i32 arithmetic wrapping as Rust's
// `wrapping_add`), so the same corners and gradients are chosen for both scalars; the sums run
// in the Rust order (the balanced tree of `corner_sum`), so over `Fx` every bit is Rust's.

// PERM: Ken Perlin's reference permutation of 0..=255, four entries a word (entry 4k + j in
// bits 8j..8j+8 of word k). A private array, not a `const` one: naga copies a constant array
// into a fresh variable for every access at an index known only at run time, and lavapipe then
// took two minutes to compile a kernel of 16 lookups; packed, the per-invocation copy of the
// private array is a quarter of the size (a third of a second less to compile).
var<private> BEE_PERM: array<u32, 64> = array<u32, 64>(
    0x5b89a097u, 0x0d830f5au, 0x35605fc9u, 0xe107e9c2u, 0x1e67248cu, 0x63088e45u,
    0x0a15f025u, 0x9406be17u, 0x4bea78f7u, 0x3ec51a00u, 0xcbdbfc5eu, 0x200b2375u,
    0x5821b139u, 0x573895edu, 0x887d14aeu, 0xaf44a8abu, 0x8647a54au, 0xa61b308bu,
    0xe79e924du, 0x7ae56f53u, 0xe685d33cu, 0x295c69dcu, 0x28f52e37u, 0x368f66f4u,
    0xa13f1941u, 0x4950d801u, 0xbb844cd1u, 0xa91259d0u, 0x8287c4c8u, 0x569fbc74u,
    0xc66d64a4u, 0x4003baadu, 0xfae2d934u, 0xca057b7cu, 0x7e769326u, 0xd45552ffu,
    0xe33bcecfu, 0x113a102fu, 0x2a1cbdb6u, 0xd5aab7dfu, 0x0298f877u, 0x46a39a2cu,
    0x9b6599ddu, 0x09ac2ba7u, 0xfd271681u, 0x6e6c6213u, 0xe8e0714fu, 0x6870b9b2u,
    0xe461f6dau, 0xc1f222fbu, 0x0c90d2eeu, 0xf1a2b3bfu, 0xeb913351u, 0x6bef0ef9u,
    0x1fd6c031u, 0x9d6ac7b5u, 0xb0cc54b8u, 0x2d327973u, 0xfe96047fu, 0x5dcdec8au,
    0x1d4372deu, 0x8df34818u, 0x424ec380u, 0xb49c3dd7u,
);

// GRAD: the 12 cube-edge gradients, padded to 16 with four of them repeated, as in the
// reference `grad(hash & 15, ...)`: component k (x, y, z) of gradient i in bits 2i..2i+2 of
// BEE_GRAD_X, _Y, _Z, coded 0 → 0, 1 → 1, 3 → −1. The table:
// (1, 1, 0), (−1, 1, 0), (1, −1, 0), (−1, −1, 0), (1, 0, 1), (−1, 0, 1), (1, 0, −1), (−1, 0, −1),
// (0, 1, 1), (0, −1, 1), (0, 1, −1), (0, −1, −1), (1, 1, 0), (0, −1, 1), (−1, 1, 0), (0, −1, −1).
const BEE_GRAD_X: u32 = 0x3100ddddu;
const BEE_GRAD_Y: u32 = 0xdddd00f5u;
const BEE_GRAD_Z: u32 = 0xc4f5f500u;

// Noise<S>: a noise value and its gradient with respect to the noise's argument.
struct BeeNoise {
    value: S,
    grad: vec3<S>,
}

// Lattice<S>: the part of Perlin noise at a point that does not depend on the seed. For each
// of the 8 corners of the lattice cell (corner c = (c & 1, c >> 1 & 1, c >> 2), offsets 0 or 1):
// its hash before the seed, the offset f − c of the point from it (x, y, z), its weight
// w_c = U(f_x)·V(f_y)·W(f_z) and the weight's gradient (x, y, z). (Rust holds the offsets and
// gradients by axis, `[[S; 8]; 3]`; here by corner: the same numbers.)
struct BeeLattice {
    hash: array<i32, 8>,
    offset: array<vec3<S>, 8>,
    weight: array<S, 8>,
    dweight: array<vec3<S>, 8>,
}

// perm: the permutation table at `i` wrapped into 0..=255.
fn bee_perm(i: i32) -> i32 {
    let k = u32(i & 255);
    return i32((BEE_PERM[k >> 2u] >> ((k & 3u) * 8u)) & 255u);
}

// One component of gradient `i` from its packed codes: 1, −1 or 0.
fn bee_grad_code(codes: u32, i: u32) -> i32 {
    let c = (codes >> (2u * i)) & 3u;
    return i32(c & 1u) - 2 * i32(c >> 1u);
}

// grad_component, the three of gradient `i` (0..16) as scalars (exact for both scalars:
// `S::from_i32` of −1, 0 or 1; Rust's f32 path loads the same values from GRAD_F32).
fn bee_grad_vec(i: u32) -> vec3<S> {
    return vec3<S>(
        s_from_i32(bee_grad_code(BEE_GRAD_X, i)),
        s_from_i32(bee_grad_code(BEE_GRAD_Y, i)),
        s_from_i32(bee_grad_code(BEE_GRAD_Z, i)),
    );
}

// fade: the quintic fade 6t⁵ − 15t⁴ + 10t³ and its derivative 30t²(t − 1)², as (f, df).
fn bee_fade(t: S) -> vec2<S> {
    let t3 = s_mul(s_mul(t, t), t);
    let f = s_mul(
        t3,
        s_add(s_mul(t, s_sub(s_mul(t, s_from_i32(6)), s_from_i32(15))), s_from_i32(10)),
    );
    let u = s_mul(t, s_sub(t, S_ONE));
    return vec2<S>(f, s_mul(s_mul(s_from_i32(30), u), u));
}

// split: the integer cell and the fraction in [0, 1] of one coordinate.
struct BeeSplit {
    cell: i32,
    frac: S,
}

fn bee_split(x: S) -> BeeSplit {
    let i = s_floor_i32(x);
    return BeeSplit(i, s_clamp_to(s_sub(x, s_from_i32(i)), S_ZERO, S_ONE));
}

// Lattice::new: the lattice cell of `p` (lattice units: one cell per unit).
fn bee_lattice_new(p: vec3<S>) -> BeeLattice {
    let sx = bee_split(p.x);
    let sy = bee_split(p.y);
    let sz = bee_split(p.z);
    let fx = bee_fade(sx.frac);
    let fy = bee_fade(sy.frac);
    let fz = bee_fade(sz.frac);
    // Per axis, for the corner offsets 0 and 1: the factor (1 − s or s), its derivative
    // (−ds or ds) and the offset (f or f − 1). (Arrays indexed at run time are variables
    // throughout: naga copies a value array for every such access.)
    var fac = array<vec3<S>, 2>(
        vec3<S>(s_sub(S_ONE, fx.x), s_sub(S_ONE, fy.x), s_sub(S_ONE, fz.x)),
        vec3<S>(fx.x, fy.x, fz.x),
    );
    var dfac = array<vec3<S>, 2>(
        vec3<S>(s_neg(fx.y), s_neg(fy.y), s_neg(fz.y)),
        vec3<S>(fx.y, fy.y, fz.y),
    );
    var off = array<vec3<S>, 2>(
        vec3<S>(sx.frac, sy.frac, sz.frac),
        vec3<S>(s_sub(sx.frac, S_ONE), s_sub(sy.frac, S_ONE), s_sub(sz.frac, S_ONE)),
    );
    var px = array<i32, 2>(bee_perm(sx.cell), bee_perm(sx.cell + 1));
    var l: BeeLattice;
    for (var c = 0u; c < 8u; c = c + 1u) {
        let cx = c & 1u;
        let cy = (c >> 1u) & 1u;
        let cz = c >> 2u;
        let a = fac[cx].x;
        let da = dfac[cx].x;
        let b = fac[cy].y;
        let db = dfac[cy].y;
        let e = fac[cz].z;
        let de = dfac[cz].z;
        l.hash[c] = bee_perm(bee_perm(px[cx] + (sy.cell + i32(cy))) + (sz.cell + i32(cz)));
        l.offset[c] = vec3<S>(off[cx].x, off[cy].y, off[cz].z);
        let be = s_mul(b, e);
        l.weight[c] = s_mul(a, be);
        l.dweight[c] = vec3<S>(
            s_mul(da, be),
            s_mul(s_mul(a, db), e),
            s_mul(s_mul(a, b), de),
        );
    }
    return l;
}

// corner_sum: Σ_c a_c·b_c + e_c·f_c over the 8 corners, summed as a balanced tree (the Rust
// order).
fn bee_corner_sum(
    a: ptr<function, array<S, 8>>,
    b: ptr<function, array<S, 8>>,
    e: ptr<function, array<S, 8>>,
    f: ptr<function, array<S, 8>>,
) -> S {
    var t: array<S, 8>;
    for (var c = 0u; c < 8u; c = c + 1u) {
        t[c] = s_add(s_mul((*a)[c], (*b)[c]), s_mul((*e)[c], (*f)[c]));
    }
    return s_add(
        s_add(s_add(t[0], t[1]), s_add(t[2], t[3])),
        s_add(s_add(t[4], t[5]), s_add(t[6], t[7])),
    );
}

// Lattice::corners: the corners' gradients g_c for `seed`, and their dot products with the
// corners' offsets.
struct BeeCorners {
    g: array<vec3<S>, 8>,
    dot: array<S, 8>,
}

fn bee_lattice_corners(l: ptr<function, BeeLattice>, seed: u32) -> BeeCorners {
    var r: BeeCorners;
    for (var c = 0u; c < 8u; c = c + 1u) {
        let i = u32(bee_perm((*l).hash[c] + i32(seed)) & 15);
        let g = bee_grad_vec(i);
        let o = (*l).offset[c];
        r.g[c] = g;
        r.dot[c] = s_add(s_add(s_mul(g.x, o.x), s_mul(g.y, o.y)), s_mul(g.z, o.z));
    }
    return r;
}

// Lattice::grad: the gradient of the noise for `seed` with respect to the point:
// Σ_c w_c g_c + Σ_c ∇w_c (g_c · (f − c)).
fn bee_lattice_grad_of(l: ptr<function, BeeLattice>, k: ptr<function, BeeCorners>) -> vec3<S> {
    var gx: array<S, 8>;
    var gy: array<S, 8>;
    var gz: array<S, 8>;
    var dx: array<S, 8>;
    var dy: array<S, 8>;
    var dz: array<S, 8>;
    for (var c = 0u; c < 8u; c = c + 1u) {
        gx[c] = (*k).g[c].x;
        gy[c] = (*k).g[c].y;
        gz[c] = (*k).g[c].z;
        dx[c] = (*l).dweight[c].x;
        dy[c] = (*l).dweight[c].y;
        dz[c] = (*l).dweight[c].z;
    }
    var w = (*l).weight;
    var dot = (*k).dot;
    return vec3<S>(
        bee_corner_sum(&w, &gx, &dx, &dot),
        bee_corner_sum(&w, &gy, &dy, &dot),
        bee_corner_sum(&w, &gz, &dz, &dot),
    );
}

fn bee_lattice_grad(l: ptr<function, BeeLattice>, seed: u32) -> vec3<S> {
    var k = bee_lattice_corners(l, seed);
    return bee_lattice_grad_of(l, &k);
}

// Lattice::noise: the noise value n = Σ_c w_c (g_c · (f − c)) and its gradient for `seed`.
fn bee_lattice_noise(l: ptr<function, BeeLattice>, seed: u32) -> BeeNoise {
    var k = bee_lattice_corners(l, seed);
    var zero: array<S, 8>;
    for (var c = 0u; c < 8u; c = c + 1u) {
        zero[c] = S_ZERO;
    }
    var w = (*l).weight;
    var dot = k.dot;
    let value = bee_corner_sum(&w, &dot, &zero, &zero);
    return BeeNoise(value, bee_lattice_grad_of(l, &k));
}

// perlin: Perlin noise at `p` (lattice units) for `seed` (a byte), with its analytic gradient:
// the reference hash P[P[P[x] + y] + z] with the seed folded in by one more permutation,
// P[hash + seed].
fn bee_perlin(p: vec3<S>, seed: u32) -> BeeNoise {
    var l = bee_lattice_new(p);
    return bee_lattice_noise(&l, seed);
}
