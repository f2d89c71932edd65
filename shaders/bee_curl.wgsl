// The curl-noise force (host-sim/src/gpu/shaders.rs, BEE_CURL): `swarm_core::bee::curl`
// (core-nostd/src/bee/curl.rs, chen §V-A, eq. 8-9), over the scalar `S`, on bee_perlin.wgsl.

// SEEDS: the three seeds of Per_1, Per_2, Per_3 (eq. 8: "a Perlin noise function with three
// random seeds"; ours).
const BEE_SEED_1: u32 = 17u;
const BEE_SEED_2: u32 = 101u;
const BEE_SEED_3: u32 = 211u;

// The three potentials ψ_1, ψ_2, ψ_3 of eq. 8 with their derivatives.
struct BeePotential {
    x: BeeNoise,
    y: BeeNoise,
    z: BeeNoise,
}

// SEEDS[k].
fn bee_seed(k: u32) -> u32 {
    return select(select(BEE_SEED_3, BEE_SEED_2, k == 1u), BEE_SEED_1, k == 0u);
}

// lattice_point: r/L, the point in lattice units.
fn bee_lattice_point(pos: vec3<S>, grid_edge: S) -> vec3<S> {
    return vec3<S>(s_div(pos.x, grid_edge), s_div(pos.y, grid_edge), s_div(pos.z, grid_edge));
}

// potential: the potential ψ of eq. 8 and its derivatives, component k ψ_k(r) = ε·Per_k(r/L)
// (noise on a lattice of edge L; the 1/L of eq. 8 appears in the derivatives by the chain rule):
// `SEEDS.map(..)` as a loop (one copy of the noise in the kernel, not three).
fn bee_potential(pos: vec3<S>, grid_edge: S, epsilon: S) -> BeePotential {
    var l = bee_lattice_new(bee_lattice_point(pos, grid_edge));
    let scale = s_div(epsilon, grid_edge);
    var psi: array<BeeNoise, 3>;
    for (var k = 0u; k < 3u; k = k + 1u) {
        let n = bee_lattice_noise(&l, bee_seed(k));
        psi[k] = BeeNoise(s_mul(epsilon, n.value), geom_vec3_mul(n.grad, scale));
    }
    return BeePotential(psi[0], psi[1], psi[2]);
}

// curl_force: the curl-noise force of eq. 9, F_curl = ∇ × ψ =
// (∂ψ_z/∂y − ∂ψ_y/∂z, ∂ψ_x/∂z − ∂ψ_z/∂x, ∂ψ_y/∂x − ∂ψ_x/∂y), the three potentials sharing one
// lattice cell (their gradients by a loop over the seeds, as bee_potential); divergence-free by
// construction (§V-A).
fn bee_curl_force(pos: vec3<S>, grid_edge: S, epsilon: S) -> vec3<S> {
    var l = bee_lattice_new(bee_lattice_point(pos, grid_edge));
    let scale = s_div(epsilon, grid_edge);
    var g: array<vec3<S>, 3>;
    for (var k = 0u; k < 3u; k = k + 1u) {
        g[k] = geom_vec3_mul(bee_lattice_grad(&l, bee_seed(k)), scale);
    }
    let px = g[0];
    let py = g[1];
    let pz = g[2];
    return vec3<S>(s_sub(pz.y, py.z), s_sub(px.z, pz.x), s_sub(py.x, px.y));
}
