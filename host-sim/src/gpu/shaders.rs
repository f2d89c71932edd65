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

/// The neighbour grid's kernels: agents sorted by cell (count, multi-level exclusive scan, a
/// stable radix sort), driven by [`GpuGrid`](super::grid::GpuGrid).
pub const GRID: Module = Module {
    name: "grid",
    source: include_str!("../../../shaders/grid.wgsl"),
    uses: &[&DISPATCH],
};

/// Every module, for the validation test.
pub const ALL: &[&Module] = &[&DISPATCH, &GRID];

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
