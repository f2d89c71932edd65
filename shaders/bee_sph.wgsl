// The SPH repulsion between bees and toward target particles (host-sim/src/gpu/shaders.rs,
// BEE_SPH): `swarm_core::bee::sph` (core-nostd/src/bee/sph.rs, chen §V-B, eq. 10-11), over the
// scalar `S`. Bees are capsules of radius r: kernels are evaluated at the gap
// s = |r_i − r_j| − 2r (clamped to ≥ 0), on q = s/h, their constants divided by h one factor at
// a time (no h³, h⁴ in fixed point).

// Kernels<S>: the two kernels for one smoothing radius h, their normalisations computed once.
struct BeeKernels {
    h: S,
    inv_h: S,
    poly6_c: S,
    spiky_c: S,
}

// gap: the capsule gap s = |r_i − r_j| − 2r of eq. 10, clamped to ≥ 0.
fn bee_gap(dist: S, radius: S) -> S {
    return s_max(s_sub(s_sub(dist, radius), radius), S_ZERO);
}

// Kernels::new: the kernels of radius `h`: 315/(64π)/h/h/h and 45/π/h/h/h/h.
fn bee_kernels_new(h: S) -> BeeKernels {
    let poly6_c = s_div(s_div(s_div(s_div(s_from_f32(315.0f), s_mul(s_from_i32(64), S_PI)), h), h), h);
    let spiky_c = s_div(s_div(s_div(s_div(s_div(s_from_i32(45), S_PI), h), h), h), h);
    return BeeKernels(h, s_div(S_ONE, h), poly6_c, spiky_c);
}

// Kernels::q: whether 0 ≤ s < h (else the kernels vanish); q itself is `bee_kernels_q_of`.
fn bee_kernels_q_some(k: BeeKernels, s: S) -> bool {
    return s >= S_ZERO && s < k.h;
}

// q = s/h as s·(1/h), at most 1 (for 0 ≤ s < h).
fn bee_kernels_q_of(k: BeeKernels, s: S) -> S {
    return s_min(s_mul(s, k.inv_h), S_ONE);
}

// Kernels::poly6: Müller's poly6 kernel (eq. 10, [61]): 315/(64π h³)·(1 − q²)³ for q < 1, else 0.
fn bee_kernels_poly6(k: BeeKernels, s: S) -> S {
    if (!bee_kernels_q_some(k, s)) {
        return S_ZERO;
    }
    let q = bee_kernels_q_of(k, s);
    let w = s_sub(S_ONE, s_mul(q, q));
    return s_mul(s_mul(s_mul(k.poly6_c, w), w), w);
}

// Kernels::spiky_grad: the magnitude of Desbrun's spiky-kernel gradient (eq. 11, [61]):
// 45/(π h⁴)·(1 − q)² for q < 1, else 0.
fn bee_kernels_spiky_grad(k: BeeKernels, s: S) -> S {
    if (!bee_kernels_q_some(k, s)) {
        return S_ZERO;
    }
    let q = bee_kernels_q_of(k, s);
    let w = s_sub(S_ONE, q);
    return s_mul(s_mul(k.spiky_c, w), w);
}

// poly6: Kernels::poly6 for one evaluation.
fn bee_poly6(s: S, h: S) -> S {
    return bee_kernels_poly6(bee_kernels_new(h), s);
}

// spiky_grad: Kernels::spiky_grad for one evaluation.
fn bee_spiky_grad(s: S, h: S) -> S {
    return bee_kernels_spiky_grad(bee_kernels_new(h), s);
}

// pressure: p = k·max(ρ − ρ0, 0) (§V-B).
fn bee_pressure(rho: S, p: BeeParams) -> S {
    return s_mul(p.stiffness, s_max(s_sub(rho, p.rest_density), S_ZERO));
}

// self_density: the density of an isolated bee, m·W_poly6(0, h): the self term of eq. 10.
fn bee_self_density(p: BeeParams) -> S {
    return s_mul(p.mass, bee_poly6(S_ZERO, p.h));
}

// term: one term of the repulsion, m·(p_i + p_j)/(2ρ_j)·|∇W_spiky|·r̂_ji, from the offset
// `diff` = r_i − r_j and its length `dist`; zero for coincident positions or outside the kernel.
fn bee_term(
    k: BeeKernels,
    diff: vec3<S>,
    dist: S,
    p_i: S,
    p_j: S,
    rho_j: S,
    p: BeeParams,
) -> vec3<S> {
    let grad = bee_kernels_spiky_grad(k, bee_gap(dist, p.radius));
    if (dist <= S_ZERO || grad <= S_ZERO) {
        return vec3<S>(S_ZERO, S_ZERO, S_ZERO);
    }
    // One division for the direction: r̂_ji = diff·(1/|diff|).
    let dir = geom_vec3_mul(diff, s_div(S_ONE, dist));
    return geom_vec3_mul(
        dir,
        s_mul(s_mul(p.mass, grad), s_div(s_add(p_i, p_j), s_add(rho_j, rho_j))),
    );
}

// pair_force: term from the two positions.
fn bee_pair_force(
    k: BeeKernels,
    r_i: vec3<S>,
    r_j: vec3<S>,
    p_i: S,
    p_j: S,
    rho_j: S,
    p: BeeParams,
) -> vec3<S> {
    let diff = geom_vec3_sub(r_i, r_j);
    return bee_term(k, diff, geom_vec3_length(diff), p_i, p_j, rho_j, p);
}

// density: ρ_i = Σ_j m_j W_poly6(|r_i − r_j| − 2r, h) of eq. 10 over the bee itself, then the
// frame's neighbours and target particles, limited to LIMIT.
fn bee_density(pos: vec3<S>, frame: ptr<function, BeeFrame>, p: BeeParams) -> S {
    let k = bee_kernels_new(p.h);
    var rho = bee_self_density(p);
    for (var i = 0u; i < (*frame).neighbours_len; i = i + 1u) {
        let d = geom_vec3_length(geom_vec3_sub(pos, (*frame).neighbours[i].pos));
        rho = s_add(rho, s_mul(p.mass, bee_kernels_poly6(k, bee_gap(d, p.radius))));
    }
    for (var i = 0u; i < (*frame).targets_len; i = i + 1u) {
        let d = geom_vec3_length(geom_vec3_sub(pos, (*frame).targets[i]));
        rho = s_add(rho, s_mul(p.mass, bee_kernels_poly6(k, bee_gap(d, p.radius))));
    }
    return s_min(rho, s_from_f32(BEE_LIMIT));
}

// repulsion: the repulsion force on bee i (eq. 11 in the symmetric form of Müller et al. 2003),
// given its new density `rho_i`: a neighbour's ρ_j is the density it broadcast, at least the
// self term; a target particle has the density of an isolated particle.
fn bee_repulsion(pos: vec3<S>, rho_i: S, frame: ptr<function, BeeFrame>, p: BeeParams) -> vec3<S> {
    let p_i = bee_pressure(rho_i, p);
    let rho_floor = bee_self_density(p);
    let k = bee_kernels_new(p.h);
    var f = vec3<S>(S_ZERO, S_ZERO, S_ZERO);
    for (var i = 0u; i < (*frame).neighbours_len; i = i + 1u) {
        let n = (*frame).neighbours[i];
        let rho_j = s_max(n.density, rho_floor);
        f = geom_vec3_add(f, bee_pair_force(k, pos, n.pos, p_i, bee_pressure(rho_j, p), rho_j, p));
    }
    let p_floor = bee_pressure(rho_floor, p);
    for (var i = 0u; i < (*frame).targets_len; i = i + 1u) {
        f = geom_vec3_add(f, bee_pair_force(k, pos, (*frame).targets[i], p_i, p_floor, rho_floor, p));
    }
    return f;
}

// The density and the repulsion of interact.
struct BeeInteraction {
    rho: S,
    force: vec3<S>,
}

// interact: density, then repulsion with that density, the same bits, each offset r_i − r_j and
// its length computed once for both.
fn bee_interact(pos: vec3<S>, frame: ptr<function, BeeFrame>, p: BeeParams) -> BeeInteraction {
    return bee_interact_with(pos, frame, p, bee_kernels_new(p.h));
}

// The frame's neighbours (entries 0..BEE_NEIGHBOURS) and target particles (entries
// BEE_NEIGHBOURS..) as one list: whether entry `j` is present, and its position.
fn bee_entry_present(frame: ptr<function, BeeFrame>, j: u32) -> bool {
    if (j < BEE_NEIGHBOURS) {
        return j < (*frame).neighbours_len;
    }
    return j - BEE_NEIGHBOURS < (*frame).targets_len;
}

fn bee_entry_pos(frame: ptr<function, BeeFrame>, j: u32) -> vec3<S> {
    if (j < BEE_NEIGHBOURS) {
        return (*frame).neighbours[j].pos;
    }
    return (*frame).targets[j - BEE_NEIGHBOURS];
}

// interact_with: interact with the kernels of radius `p.h` computed beforehand. The neighbours
// then the target particles in one loop (the Rust order of the sums; one copy of the kernels'
// code in the kernel, not two).
fn bee_interact_with(
    pos: vec3<S>,
    frame: ptr<function, BeeFrame>,
    p: BeeParams,
    k: BeeKernels,
) -> BeeInteraction {
    // The offsets of the neighbours and of the target particles, and the density (eq. 10).
    var diff: array<vec3<S>, BEE_NEIGHBOURS + BEE_TARGETS>;
    var dist: array<S, BEE_NEIGHBOURS + BEE_TARGETS>;
    let rho_floor = s_mul(p.mass, bee_kernels_poly6(k, S_ZERO));
    var rho = rho_floor;
    for (var j = 0u; j < BEE_NEIGHBOURS + BEE_TARGETS; j = j + 1u) {
        if (bee_entry_present(frame, j)) {
            diff[j] = geom_vec3_sub(pos, bee_entry_pos(frame, j));
            dist[j] = geom_vec3_length(diff[j]);
            rho = s_add(rho, s_mul(p.mass, bee_kernels_poly6(k, bee_gap(dist[j], p.radius))));
        }
    }
    let rho_i = s_min(rho, s_from_f32(BEE_LIMIT));
    // The repulsion (eq. 11): a neighbour's density is at least the self term, a target
    // particle's is the self term (and its pressure pressure(rho_floor), the Rust p_floor).
    let p_i = bee_pressure(rho_i, p);
    var force = vec3<S>(S_ZERO, S_ZERO, S_ZERO);
    for (var j = 0u; j < BEE_NEIGHBOURS + BEE_TARGETS; j = j + 1u) {
        if (bee_entry_present(frame, j)) {
            var rho_j = rho_floor;
            if (j < BEE_NEIGHBOURS) {
                rho_j = s_max((*frame).neighbours[j].density, rho_floor);
            }
            let t = bee_term(k, diff[j], dist[j], p_i, bee_pressure(rho_j, p), rho_j, p);
            force = geom_vec3_add(force, t);
        }
    }
    return BeeInteraction(rho_i, force);
}
