//! The WGSL files of `shaders/`, and kernels put together from them.
//!
//! WGSL has no `#include`: a kernel's source is its own text after the text of every module it
//! uses ([`compose`]), each module once, the modules it uses before it. Every function of a
//! module is prefixed with the module's name (`fx_mul`, `rand_unit`), so modules never clash.
//! The naga test of this module parses and validates every module and every kernel without a
//! GPU.
//!
//! WGSL has no generics either: the modules written over the controllers' scalar (`geom`,
//! `rand`'s `rand_unit`, the ant and bee controllers; [`Module::over_scalar`]) call the scalar `S` and
//! its operations `s_add`, `s_sqrt`, ... by name, and a kernel composes exactly one *scalar
//! module* with them: [`SCALAR_FX`] (`S = i32`, the bits of an `Fx`, bit for bit) or
//! [`SCALAR_F32`] (`S = f32`, measured): `compose(&[&SCALAR_FX, &GEOM], kernel)`.

/// One WGSL file of `shaders/`.
#[derive(Debug)]
pub struct Module {
    /// Its name (the file is `shaders/<name>.wgsl`).
    pub name: &'static str,
    /// Its text.
    pub source: &'static str,
    /// The modules its functions call.
    pub uses: &'static [&'static Module],
    /// Whether it is written over the scalar `S`: a kernel that uses it composes one of
    /// [`SCALARS`] too (which one is the kernel's choice, so it is not in `uses`).
    pub over_scalar: bool,
}

/// The threads of a dispatch: `thread_index` numbers them across a 2D grid of workgroups (a
/// dimension holds at most 65,535 workgroups), `WORKGROUP` threads per workgroup.
pub const DISPATCH: Module = Module {
    name: "dispatch",
    source: include_str!("../../../shaders/dispatch.wgsl"),
    uses: &[],
    over_scalar: false,
};

/// I16F16 fixed point: the arithmetic of [`swarm_core::Fx`] (`core-nostd/src/scalar/fx.rs`) and
/// the provided methods of [`swarm_core::Scalar`] (`core-nostd/src/scalar/mod.rs`), on the raw
/// `i32` bits, bit for bit (`fx_add`, `fx_mul`, `fx_div`, `fx_sqrt`, `fx_sin`, `fx_atan2`,
/// `fx_exp`, ..., constants `FX_ONE`, `FX_PI`, ...; 64-bit integers as `vec2<u32>` words).
pub const FX: Module = Module {
    name: "fx",
    source: include_str!("../../../shaders/fx.wgsl"),
    uses: &[],
    over_scalar: false,
};

/// The scalar `S` as I16F16 fixed point: the [`swarm_core::Scalar`] interface of
/// [`swarm_core::Fx`] (`alias S = i32`, the bits; `s_add`, `s_mul`, `s_sqrt`, `s_sin_cos`,
/// `s_from_f32`, ..., `S_ZERO`, `S_ONE`, `S_EPS`, `S_PI`, `S_DIRECT_LENGTH`) on the `fx_`
/// functions: the generic modules composed with it give the bits of the Rust code for `Fx`.
pub const SCALAR_FX: Module = Module {
    name: "scalar_fx",
    source: include_str!("../../../shaders/scalar_fx.wgsl"),
    uses: &[&FX],
    over_scalar: false,
};

/// The scalar `S` as `f32`: the same names as [`SCALAR_FX`] with the semantics of the `f32`
/// [`swarm_core::Scalar`] (conversions, `floor_i32`, `unit_open`, `abs`, `min`, `max` exact;
/// `sqrt`, the trigonometry, `exp` and the rounding of fused operations left to the GPU:
/// measured, not promised).
pub const SCALAR_F32: Module = Module {
    name: "scalar_f32",
    source: include_str!("../../../shaders/scalar_f32.wgsl"),
    uses: &[],
    over_scalar: false,
};

/// The scalar modules: a kernel of modules [`Module::over_scalar`] composes one of them.
pub const SCALARS: &[&Module] = &[&SCALAR_FX, &SCALAR_F32];

/// Counter-based random numbers: [`swarm_core::rand`] (`core-nostd/src/rand.rs`), bit for bit
/// (`rand_mix32`, `rand_rand`, the stream constants `RAND_ANT_STOP`, ..., `StepCtx`, and over
/// the scalar `rand_unit`, `rand_angle`, `rand_chance`).
pub const RAND: Module = Module {
    name: "rand",
    source: include_str!("../../../shaders/rand.wgsl"),
    uses: &[],
    over_scalar: true,
};

/// Small vectors over the scalar: [`swarm_core::geom`] (`core-nostd/src/geom.rs`), bit for bit
/// for `S = Fx`: `Vec2` as `vec2<S>` (`geom_dot`, `geom_length`, `geom_normalized`, ...), `Vec3`
/// as `vec3<S>` (`geom_vec3_*`), `Rect` as `GeomRect` (`geom_rect_*`); `S_DIRECT_LENGTH`
/// chooses the length computation as `Scalar::DIRECT_LENGTH` does.
pub const GEOM: Module = Module {
    name: "geom",
    source: include_str!("../../../shaders/geom.wgsl"),
    uses: &[],
    over_scalar: true,
};

/// The ant's state: [`swarm_core::ant::AntState`] (`core-nostd/src/ant/state.rs`) as
/// `AntState` over the scalar, its validation (`ant_state_validate`, `ant_check_point`, ...),
/// the enums' discriminants (`ANT_LABEL_*`, ...) and the status words of the errors
/// (`ANT_ERROR_*`, `ANT_FIELD_*`, decoded by [`crate::gpu::ant::layout::status_error`]).
pub const ANT_STATE: Module = Module {
    name: "ant_state",
    source: include_str!("../../../shaders/ant_state.wgsl"),
    uses: &[&GEOM],
    over_scalar: true,
};

/// The ant controller's parameters: [`swarm_core::ant::AntParams`] as `AntParams`.
pub const ANT_PARAMS: Module = Module {
    name: "ant_params",
    source: include_str!("../../../shaders/ant_params.wgsl"),
    uses: &[],
    over_scalar: true,
};

/// The ant's sensor frames with the simulator's capacities: `core-nostd/src/ant/frame.rs`
/// (`AntPlanFrame`, `AntResolveFrame`, `ant_plan_frame_validate`, ...).
pub const ANT_FRAME: Module = Module {
    name: "ant_frame",
    source: include_str!("../../../shaders/ant_frame.wgsl"),
    uses: &[&ANT_STATE],
    over_scalar: true,
};

/// Obstacles: `core-nostd/src/ant/obstacle.rs` (`ant_obstacle_heading`, `ant_constrain`, ...).
pub const ANT_OBSTACLE: Module = Module {
    name: "ant_obstacle",
    source: include_str!("../../../shaders/ant_obstacle.wgsl"),
    uses: &[&ANT_FRAME, &ANT_PARAMS, &RAND],
    over_scalar: true,
};

/// Interactions: `core-nostd/src/ant/interact.rs` (`ant_transfers`, `ant_informer`,
/// `ant_environment`, ...).
pub const ANT_INTERACT: Module = Module {
    name: "ant_interact",
    source: include_str!("../../../shaders/ant_interact.wgsl"),
    uses: &[&ANT_OBSTACLE],
    over_scalar: true,
};

/// Phase 1 of the ant tick: `core-nostd/src/ant/plan.rs` (`ant_plan_checked`, `ant_predict`).
pub const ANT_PLAN: Module = Module {
    name: "ant_plan",
    source: include_str!("../../../shaders/ant_plan.wgsl"),
    uses: &[&ANT_INTERACT],
    over_scalar: true,
};

/// Phase 2 of the ant tick: `core-nostd/src/ant/resolve.rs` (`ant_resolve_checked`,
/// `ant_repulsion`).
pub const ANT_RESOLVE: Module = Module {
    name: "ant_resolve",
    source: include_str!("../../../shaders/ant_resolve.wgsl"),
    uses: &[&ANT_PLAN, &ANT_OBSTACLE],
    over_scalar: true,
};

/// The ant values as `u32` words, the layout of [`crate::gpu::ant::layout`]
/// (`ant_state_from_words`, `ant_plan_to_words`, ...; `ANT_STATE_WORDS`, ...).
pub const ANT_LAYOUT: Module = Module {
    name: "ant_layout",
    source: include_str!("../../../shaders/ant_layout.wgsl"),
    uses: &[&ANT_PLAN, &ANT_FRAME, &ANT_PARAMS],
    over_scalar: true,
};

/// The ant world as `u32` words, the layout of [`crate::gpu::ant::world`] (binding 1): its
/// objects (`ant_world_object`; polygon edges with their precomputed normal, direction and
/// length, `ant_world_edge`), the arena, the ranges, the route (`ant_world_target_of`) and the
/// grid's cell of a point over the scalar (`ant_world_cell`).
pub const ANT_WORLD: Module = Module {
    name: "ant_world",
    source: include_str!("../../../shaders/ant_world.wgsl"),
    uses: &[&GEOM],
    over_scalar: true,
};

/// What an ant senses: `host-sim/src/ants/sense.rs` and the object geometry of
/// `host-sim/src/ants/world.rs` over the scalar (`ant_plan_frame`, `ant_resolve_frame`,
/// `ant_sense_closest`, `ant_sense_surface`, `ant_sense_pieces_within`), from the sensed ants
/// (struct of arrays) and the GPU grid; bit for bit over `Fx`. Driven by
/// [`AntSense`](crate::gpu::ant::sense::AntSense).
pub const ANT_SENSE: Module = Module {
    name: "ant_sense",
    source: include_str!("../../../shaders/ant_sense.wgsl"),
    uses: &[&ANT_WORLD, &ANT_FRAME],
    over_scalar: true,
};

/// The ant tick of the GPU engine ([`GpuAntSim`](crate::gpu::ant::engine::GpuAntSim)): the
/// kernels `ant_tick_plan_main` and `ant_tick_resolve_main` (sense and decide in one pass),
/// `ant_tick_commit_main` (events, route, states made current) and `ant_tick_end_main` (food
/// taken, the first refusal kept), on the states kept on the GPU.
pub const ANT_TICK: Module = Module {
    name: "ant_tick",
    source: include_str!("../../../shaders/ant_tick.wgsl"),
    uses: &[&DISPATCH, &ANT_SENSE, &ANT_RESOLVE, &ANT_LAYOUT],
    over_scalar: true,
};

/// The bee controller's parameters: [`swarm_core::bee::BeeParams`] as `BeeParams` (and
/// `BEE_LIMIT`).
pub const BEE_PARAMS: Module = Module {
    name: "bee_params",
    source: include_str!("../../../shaders/bee_params.wgsl"),
    uses: &[],
    over_scalar: true,
};

/// The bee's state, frame (with the simulator's capacities) and decision:
/// `core-nostd/src/bee/frame.rs` (`BeeState`, `BeeFrame`, `BeeDecision`, `bee_state_validate`,
/// `bee_frame_validate`) and the status words of the errors (`BEE_ERROR_*`, `BEE_FIELD_*`,
/// decoded by [`crate::gpu::bee::layout::status_error`]).
pub const BEE_FRAME: Module = Module {
    name: "bee_frame",
    source: include_str!("../../../shaders/bee_frame.wgsl"),
    uses: &[&GEOM, &BEE_PARAMS],
    over_scalar: true,
};

/// 3D Perlin noise with its analytic gradient: `core-nostd/src/bee/perlin.rs` (`bee_perlin`,
/// `BeeLattice`, `bee_lattice_new`, `bee_lattice_noise`, `bee_lattice_grad`). Self-contained
/// (only [`GEOM`]), for any model's noise.
pub const BEE_PERLIN: Module = Module {
    name: "bee_perlin",
    source: include_str!("../../../shaders/bee_perlin.wgsl"),
    uses: &[&GEOM],
    over_scalar: true,
};

/// The curl-noise force of chen eq. 8-9: `core-nostd/src/bee/curl.rs` (`bee_potential`,
/// `bee_curl_force`), on [`BEE_PERLIN`] alone.
pub const BEE_CURL: Module = Module {
    name: "bee_curl",
    source: include_str!("../../../shaders/bee_curl.wgsl"),
    uses: &[&BEE_PERLIN],
    over_scalar: true,
};

/// The SPH density and repulsion: `core-nostd/src/bee/sph.rs` (`BeeKernels`, `bee_density`,
/// `bee_repulsion`, `bee_interact_with`, ...).
pub const BEE_SPH: Module = Module {
    name: "bee_sph",
    source: include_str!("../../../shaders/bee_sph.wgsl"),
    uses: &[&BEE_FRAME],
    over_scalar: true,
};

/// Roll-to-avoidance: `core-nostd/src/bee/vision.rs` (`bee_near`, `bee_in_view`, `bee_ramp`,
/// `bee_tune_velocity`, `bee_avoidance_roll_deg`, ...).
pub const BEE_VISION: Module = Module {
    name: "bee_vision",
    source: include_str!("../../../shaders/bee_vision.wgsl"),
    uses: &[&BEE_FRAME],
    over_scalar: true,
};

/// Body oscillation: `core-nostd/src/bee/oscillation.rs` (`bee_pitch_deg`, `bee_roll_deg`,
/// `bee_forward_axis`, `bee_oscillation_force`, ...).
pub const BEE_OSCILLATION: Module = Module {
    name: "bee_oscillation",
    source: include_str!("../../../shaders/bee_oscillation.wgsl"),
    uses: &[&GEOM, &BEE_PARAMS],
    over_scalar: true,
};

/// One step of the bee controller: `core-nostd/src/bee/step.rs` (`bee_step_checked`,
/// `bee_step_with`, `BeeStepConsts`).
pub const BEE_STEP: Module = Module {
    name: "bee_step",
    source: include_str!("../../../shaders/bee_step.wgsl"),
    uses: &[&BEE_OSCILLATION, &BEE_VISION, &BEE_SPH, &BEE_CURL],
    over_scalar: true,
};

/// The bee values as `u32` words, the layout of [`crate::gpu::bee::layout`]
/// (`bee_state_from_words`, `bee_frame_from_words`, ...; `BEE_STATE_WORDS`, ...).
pub const BEE_LAYOUT: Module = Module {
    name: "bee_layout",
    source: include_str!("../../../shaders/bee_layout.wgsl"),
    uses: &[&BEE_STEP],
    over_scalar: true,
};

/// The bee world as `u32` words, the layout of [`crate::gpu::bee::world`] (binding 1): its
/// obstacles (`bee_world_obstacle`) and their geometry over the scalar (`bee_world_surface`:
/// `sphere_surface`, `box_surface_open`, `shaft_surface_open` of `host-sim/src/bees/world.rs`),
/// the targets (`bee_world_target_center`), their particles sorted by cell, the ranges, the
/// bounds and the grids' cells of a point over the scalar (`bee_world_cell`).
pub const BEE_WORLD: Module = Module {
    name: "bee_world",
    source: include_str!("../../../shaders/bee_world.wgsl"),
    uses: &[&GEOM],
    over_scalar: true,
};

/// What a bee senses: `host-sim/src/bees/sense.rs` over the scalar (`bee_sense_frame`, the
/// frame of `bee_frame`; `bee_sense_neighbours`, `bee_sense_particles`, `bee_sense_obstacle`),
/// from the sensed bees (struct of arrays), the GPU grid and the world's words; bit for bit over
/// `Fx`. Driven by [`BeeSense`](crate::gpu::bee::sense::BeeSense).
pub const BEE_SENSE: Module = Module {
    name: "bee_sense",
    source: include_str!("../../../shaders/bee_sense.wgsl"),
    uses: &[&BEE_WORLD, &BEE_FRAME],
    over_scalar: true,
};

/// The 3D world's corrections: `host-sim/src/space.rs`'s `confine` over the scalar
/// (`space_confine`, with `space_may_be_within` on the confinement boxes of
/// [`confine_boxes`](super::space::confine_boxes), binding 15), on the obstacles of
/// [`BEE_WORLD`]; used by the bee and wang2014 ticks.
pub const SPACE: Module = Module {
    name: "space",
    source: include_str!("../../../shaders/space.wgsl"),
    uses: &[&BEE_WORLD],
    over_scalar: true,
};

/// The bee tick of the GPU engine ([`GpuBeeSim`](crate::gpu::bee::engine::GpuBeeSim)): the
/// kernels `bee_tick_step_main` (sense and step in one pass: `bee_sense_frame`, then
/// `bee_step_checked`) and `bee_tick_commit_main` (the world's corrections of
/// `host-sim/src/bees/world.rs`'s `BeeWorld::confine`, counted; the states made current and
/// sensed; the first refusal kept), on the states kept on the GPU.
pub const BEE_TICK: Module = Module {
    name: "bee_tick",
    source: include_str!("../../../shaders/bee_tick.wgsl"),
    uses: &[&DISPATCH, &BEE_SENSE, &BEE_LAYOUT, &SPACE],
    over_scalar: true,
};

/// The wang2014 controller: [`swarm_core::wang`] (`core-nostd/src/wang/`) over the scalar
/// (`wang_advect_checked`, `wang_separate_checked`, the bounded curl noise `wang_curl_noise`
/// and its baselines, the frames' validation with status words), on the bee model's Perlin
/// potential and ramp as the Rust is; bit for bit over `Fx`.
pub const WANG_STEP: Module = Module {
    name: "wang_step",
    source: include_str!("../../../shaders/wang_step.wgsl"),
    uses: &[&BEE_CURL, &BEE_VISION, &RAND],
    over_scalar: true,
};

/// The wang2014 tick of the GPU engine ([`GpuWangSim`](crate::gpu::wang::engine::GpuWangSim)):
/// the kernels `wang_tick_advect_main` (the advect frame: `CostField::guide_at` on the fields'
/// words, `WangWorld::boundary`; the step; the world's corrections of x*, its MDE grid cell),
/// `wang_tick_separate_main` (the nearest x* within d_min, minimum distance enforcement) and
/// `wang_tick_commit_main` (the world's corrections, counted; the first refusal kept).
pub const WANG_TICK: Module = Module {
    name: "wang_tick",
    source: include_str!("../../../shaders/wang_tick.wgsl"),
    uses: &[&DISPATCH, &WANG_STEP, &BEE_SENSE, &SPACE],
    over_scalar: true,
};

/// The ren2016 insect: [`swarm_core::fly`] (`core-nostd/src/fly/`: the frame's validation, the
/// zone forces of Eq. 5, friction, the stimulus response with its escape draw, the noise
/// sources; the step of Algorithm 1) and the 3D ORCA it calls (`core-nostd/src/orca3d/`: the
/// neighbour and obstacle planes, RVO2-3D's `linearProgram1..4`, `solve`) over the scalar
/// (`fly_step_checked`), on the bee model's curl noise and number checks and wang's unit check
/// (`check_unit`); bit for bit over `Fx`.
pub const FLY_STEP: Module = Module {
    name: "fly_step",
    source: include_str!("../../../shaders/fly_step.wgsl"),
    uses: &[&WANG_STEP],
    over_scalar: true,
};

/// The ren2016 tick of the GPU engine ([`GpuFlySim`](crate::gpu::fly::engine::GpuFlySim)): the
/// kernels `fly_tick_cells_main` (the grid's cells), `fly_tick_step_main` (the frame of
/// `host-sim/src/fly/sense.rs` on the GPU grid and the world's words, then `fly_step_checked`)
/// and `fly_tick_commit_main` (the world's corrections, counted; the first refusal kept).
pub const FLY_TICK: Module = Module {
    name: "fly_tick",
    source: include_str!("../../../shaders/fly_tick.wgsl"),
    uses: &[&DISPATCH, &FLY_STEP, &FLY_SURFACES, &SPACE],
    over_scalar: true,
};

/// The obstacle surfaces of a 3D insect's frame (`World3d::surfaces`: every obstacle and wall
/// within ORCA's reach, nearest first), into the fly's frame; the ren2016 and li2015 ticks
/// sense them alike.
pub const FLY_SURFACES: Module = Module {
    name: "fly_surfaces",
    source: include_str!("../../../shaders/fly_surfaces.wgsl"),
    uses: &[&FLY_STEP, &BEE_SENSE],
    over_scalar: true,
};

/// The li2015 insect: [`swarm_core::li`] (`core-nostd/src/li/`: the learned tables' draws,
/// the density grid, Algorithm 1 with the Metropolis-Hastings screening, the step) over the
/// scalar (`li_step_checked`), on the fly's 3D ORCA and frame validation; bit for bit over
/// `Fx`.
pub const LI_STEP: Module = Module {
    name: "li_step",
    source: include_str!("../../../shaders/li_step.wgsl"),
    uses: &[&FLY_STEP],
    over_scalar: true,
};

/// The li2015 tick of the GPU engine ([`GpuLiSim`](crate::gpu::li::GpuLiSim)): the kernels
/// `li_tick_cells_main` (the grid's cells), `li_tick_step_main` (the frame of `li_frame` on the
/// GPU grid and the world's words, then `li_step_checked`) and `li_tick_commit_main` (the
/// world's corrections, counted; the first refusal kept).
pub const LI_TICK: Module = Module {
    name: "li_tick",
    source: include_str!("../../../shaders/li_tick.wgsl"),
    uses: &[&DISPATCH, &LI_STEP, &FLY_SURFACES, &SPACE],
    over_scalar: true,
};

/// The neighbour grid's kernels: agents sorted by cell (count, multi-level exclusive scan, a
/// stable radix sort), driven by [`GpuGrid`](super::grid::GpuGrid).
pub const GRID: Module = Module {
    name: "grid",
    source: include_str!("../../../shaders/grid.wgsl"),
    uses: &[&DISPATCH],
    over_scalar: false,
};

/// Every module, for the validation test.
pub const ALL: &[&Module] = &[
    &DISPATCH,
    &FX,
    &SCALAR_FX,
    &SCALAR_F32,
    &RAND,
    &GEOM,
    &ANT_STATE,
    &ANT_PARAMS,
    &ANT_FRAME,
    &ANT_OBSTACLE,
    &ANT_INTERACT,
    &ANT_PLAN,
    &ANT_RESOLVE,
    &ANT_LAYOUT,
    &ANT_WORLD,
    &ANT_SENSE,
    &ANT_TICK,
    &BEE_PARAMS,
    &BEE_FRAME,
    &BEE_PERLIN,
    &BEE_CURL,
    &BEE_SPH,
    &BEE_VISION,
    &BEE_OSCILLATION,
    &BEE_STEP,
    &BEE_LAYOUT,
    &BEE_WORLD,
    &BEE_SENSE,
    &BEE_TICK,
    &SPACE,
    &WANG_STEP,
    &WANG_TICK,
    &FLY_STEP,
    &FLY_TICK,
    &FLY_SURFACES,
    &LI_STEP,
    &LI_TICK,
    &GRID,
];

/// Threads per workgroup of every kernel (`WORKGROUP` in `dispatch.wgsl`).
pub const WORKGROUP: u32 = 64;

/// `kernel`'s text after the text of every module in `uses` and of the modules they use, each
/// once, dependencies first.
pub fn compose(uses: &[&Module], kernel: &str) -> String {
    fn visit(m: &Module, seen: &mut Vec<&'static str>, out: &mut String) {
        if seen.contains(&m.name) {
            return;
        }
        for d in m.uses {
            visit(d, seen, out);
        }
        seen.push(m.name);
        out.push_str("// ---- shaders/");
        out.push_str(m.name);
        out.push_str(".wgsl ----\n");
        out.push_str(m.source);
        out.push('\n');
    }
    let mut seen = Vec::new();
    let mut out = String::new();
    for m in uses {
        visit(m, &mut seen, &mut out);
    }
    out.push_str("// ---- kernel ----\n");
    out.push_str(kernel);
    out
}

#[cfg(test)]
pub(crate) mod tests {
    use super::*;

    /// Parses and validates `source` with naga, as wgpu would; the diagnostic on failure.
    pub(crate) fn validate(what: &str, source: &str) {
        let module = naga::front::wgsl::parse_str(source)
            .unwrap_or_else(|e| panic!("{what}: {}", e.emit_to_string(source)));
        naga::valid::Validator::new(
            naga::valid::ValidationFlags::all(),
            naga::valid::Capabilities::empty(),
        )
        .validate(&module)
        .unwrap_or_else(|e| panic!("{what}: {}", e.emit_to_string(source)));
    }

    /// Every module, a module over the scalar composed with each scalar module.
    #[test]
    fn every_module_is_valid_wgsl() {
        for m in ALL {
            if m.over_scalar {
                for scalar in SCALARS {
                    validate(
                        &format!("{} over {}", m.name, scalar.name),
                        &compose(&[scalar, m], ""),
                    );
                }
            } else {
                validate(m.name, &compose(&[m], ""));
            }
        }
    }

    /// The two scalar modules declare the same names (so a generic module composes with
    /// either), and nothing else declares the scalar's names.
    #[test]
    fn the_scalar_modules_have_one_interface() {
        fn names(source: &str) -> Vec<String> {
            let mut v: Vec<String> = source
                .lines()
                .filter_map(|l| {
                    let l = l.trim_start();
                    ["fn ", "const ", "alias "]
                        .iter()
                        .find_map(|k| l.strip_prefix(k))
                        .map(|rest| {
                            rest.split(|c: char| !(c.is_alphanumeric() || c == '_'))
                                .next()
                                .unwrap_or_default()
                                .to_string()
                        })
                })
                .filter(|n| n == "S" || n.starts_with("s_") || n.starts_with("S_"))
                .collect();
            v.sort();
            v
        }
        let fx = names(SCALAR_FX.source);
        assert!(fx.len() > 30, "{fx:?}");
        // `s_f32_is_nan` is scalar_f32's own helper.
        let f32: Vec<String> = names(SCALAR_F32.source)
            .into_iter()
            .filter(|n| n != "s_f32_is_nan")
            .collect();
        assert_eq!(fx, f32);
        for m in ALL
            .iter()
            .filter(|m| !SCALARS.iter().any(|s| s.name == m.name))
        {
            assert!(
                names(m.source).is_empty(),
                "{} declares a scalar name",
                m.name
            );
        }
    }

    #[test]
    fn compose_puts_each_module_once_dependencies_first() {
        const A: Module = Module {
            name: "a",
            source: "fn a_f() {}",
            uses: &[],
            over_scalar: false,
        };
        const B: Module = Module {
            name: "b",
            source: "fn b_f() { a_f(); }",
            uses: &[&A],
            over_scalar: false,
        };
        let s = compose(&[&B, &A], "fn k() { b_f(); }");
        assert_eq!(s.matches("fn a_f").count(), 1);
        assert!(s.find("fn a_f").unwrap() < s.find("fn b_f").unwrap());
        assert!(s.ends_with("fn k() { b_f(); }"));
    }

    #[test]
    fn the_workgroup_size_is_the_shaders() {
        assert!(
            DISPATCH
                .source
                .contains(&format!("const WORKGROUP: u32 = {WORKGROUP}u;"))
        );
    }
}
