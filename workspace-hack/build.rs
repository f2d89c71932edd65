// Cargo resolves `[build-dependencies]` (the host side of the feature unification: syn for the
// proc macros) only for a package with a build script.
fn main() {}
