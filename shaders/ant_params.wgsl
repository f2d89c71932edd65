// The ant controller's parameters (host-sim/src/gpu/shaders.rs, ANT_PARAMS):
// `swarm_core::ant::AntParams` (core-nostd/src/ant/params.rs, xiang2018 §4), over the scalar
// `S`. The kernels run the `*_checked` functions: the host validates the parameters once
// (`AntParams::checked`), as the CPU engine does, and the kernels never check them again.

// AntParams<S> (`casual_stop_ticks`, `collect_ticks`, `drop_ticks` are u16, `k` a u8).
struct AntParams {
    // Moving speed v (units/s).
    speed: S,
    // Time step Δt (s), eq. 1.
    dt: S,
    // Critical deviation angle θ of the random turn (rad), §4.1.
    theta: S,
    // Casual-stop probability per tick, §4.1.
    p_stop: S,
    casual_stop_ticks: u32,
    collect_ticks: u32,
    drop_ticks: u32,
    // Radius within which two ants touch and transfer information (§4.2.1).
    contact_range: S,
    // Distance at which an obstacle ahead triggers avoidance (§4.2.2).
    avoid_range: S,
    // Predicted distance below which another ant could collide (n_c of eq. 3).
    collision_range: S,
    // w0 of eq. 2.
    w0: S,
    // C of eq. 3.
    c: S,
    // k of eq. 3.
    k: u32,
}
