// The bee controller's parameters (host-sim/src/gpu/shaders.rs, BEE_PARAMS):
// `swarm_core::bee::BeeParams` (core-nostd/src/bee/params.rs, chen Table I and our constants),
// over the scalar `S`. The kernels run `bee_step_checked`: the host validates the parameters
// once (`BeeParams::checked`), as the CPU engine does, and the kernels never check them again.

// LIMIT: the largest magnitude accepted for any input number or parameter.
const BEE_LIMIT: f32 = 16000.0f;
// MIN_POSITIVE: the smallest value of the strictly positive parameters (host-side validation).
const BEE_MIN_POSITIVE: f32 = 0.01f;

// BeeParams<S>, in the Rust field order.
struct BeeParams {
    // h: SPH kernel radius (eq. 10-11).
    h: S,
    // L: edge length of the noise lattice (eq. 8).
    grid_edge: S,
    // κ1, κ2, κ3: weights of F_o, F_curl and F_repul (eq. 1).
    kappa1: S,
    kappa2: S,
    kappa3: S,
    // ε: magnitude of the Perlin potentials (eq. 8).
    epsilon: S,
    // m: mass of a bee and of a target particle.
    mass: S,
    // g: gravity in the thrust and sway of eq. 2.
    gravity: S,
    // ρ and A: air density and wing area in the lift of eq. 2.
    air_density: S,
    wing_area: S,
    // r: radius of the bee's capsule (eq. 10-11).
    radius: S,
    // d0: distance threshold of obstacle avoidance (eq. 5-6).
    d0: S,
    // Δt: time step (§III).
    dt: S,
    // k and ρ0: pressure stiffness and rest density, p = k·max(ρ − ρ0, 0) (§V-B).
    stiffness: S,
    rest_density: S,
    // The speed limit of u*.
    max_speed: S,
    // c: linear drag rate, F_drag = −m·c·u (ours).
    damping: S,
}
