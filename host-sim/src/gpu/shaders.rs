//! The WGSL files of `shaders/`, and kernels put together from them.
//!
//! WGSL has no `#include`: a kernel's source is its own text after the text of every module it
//! uses ([`compose`]), each module once, the modules it uses before it. Every function of a
//! module is prefixed with the module's name (`fx_mul`, `rand_unit`), so modules never clash.
//! The naga test of this module parses and validates every module and every kernel without a
//! GPU.

/// One WGSL file of `shaders/`.
#[derive(Debug)]
pub struct Module {
    /// Its name (the file is `shaders/<name>.wgsl`).
    pub name: &'static str,
    /// Its text.
    pub source: &'static str,
    /// The modules its functions call.
    pub uses: &'static [&'static Module],
}

/// The threads of a dispatch: `thread_index` numbers them across a 2D grid of workgroups (a
/// dimension holds at most 65,535 workgroups), `WORKGROUP` threads per workgroup.
pub const DISPATCH: Module = Module {
    name: "dispatch",
    source: include_str!("../../../shaders/dispatch.wgsl"),
    uses: &[],
};

/// I16F16 fixed point: the arithmetic of [`swarm_core::Fx`] (`core-nostd/src/scalar/fx.rs`) and
/// the provided methods of [`swarm_core::Scalar`] (`core-nostd/src/scalar/mod.rs`), on the raw
/// `i32` bits, bit for bit (`fx_add`, `fx_mul`, `fx_div`, `fx_sqrt`, `fx_sin`, `fx_atan2`,
/// `fx_exp`, ..., constants `FX_ONE`, `FX_PI`, ...; 64-bit integers as `vec2<u32>` words).
pub const FX: Module = Module {
    name: "fx",
    source: include_str!("../../../shaders/fx.wgsl"),
    uses: &[],
};

/// Counter-based random numbers: [`swarm_core::rand`] (`core-nostd/src/rand.rs`), bit for bit
/// (`rand_mix32`, `rand_rand`, `rand_unit_fx`, `rand_angle_fx`, `rand_chance_fx`, the stream
/// constants `RAND_ANT_STOP`, ...).
pub const RAND: Module = Module {
    name: "rand",
    source: include_str!("../../../shaders/rand.wgsl"),
    uses: &[&FX],
};

/// Small vectors over `Fx`: [`swarm_core::geom`] (`core-nostd/src/geom.rs`) for `S = Fx`, bit
/// for bit: `Vec2` as `vec2<i32>` (`geom_dot`, `geom_length`, `geom_normalized`, ...), `Vec3`
/// as `vec3<i32>` (`geom_vec3_*`), `Rect` as `GeomRect` (`geom_rect_*`).
pub const GEOM: Module = Module {
    name: "geom",
    source: include_str!("../../../shaders/geom.wgsl"),
    uses: &[&FX],
};

/// The neighbour grid's kernels: agents sorted by cell (count, multi-level exclusive scan, a
/// stable radix sort), driven by [`GpuGrid`](super::grid::GpuGrid).
pub const GRID: Module = Module {
    name: "grid",
    source: include_str!("../../../shaders/grid.wgsl"),
    uses: &[&DISPATCH],
};

/// Every module, for the validation test.
pub const ALL: &[&Module] = &[&DISPATCH, &FX, &RAND, &GEOM, &GRID];

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

    #[test]
    fn every_module_is_valid_wgsl() {
        for m in ALL {
            validate(m.name, &compose(&[m], ""));
        }
    }

    #[test]
    fn compose_puts_each_module_once_dependencies_first() {
        const A: Module = Module {
            name: "a",
            source: "fn a_f() {}",
            uses: &[],
        };
        const B: Module = Module {
            name: "b",
            source: "fn b_f() { a_f(); }",
            uses: &[&A],
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
