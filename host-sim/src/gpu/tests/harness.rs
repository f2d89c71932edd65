//! What the ant and bee tests of the GPU share: the scalars as the tests need them
//! ([`TestScalar`]), kernels made once per scalar ([`PerScalar`]), the built-in scenarios
//! shortened and their exchanges decoded, and the comparison of a kernel's output words with
//! Rust's ([`Compared`]).

use std::fmt::{Debug, Display, LowerHex};
use std::sync::OnceLock;

use serde::de::DeserializeOwned;
use swarm_core::wire::decode_payload;
use swarm_core::{Fx, ScalarKind};

use crate::ants::AntGroup;
use crate::bees::BeeGroup;
use crate::engine::Exchange;
use crate::gpu::shaders::{self, Module, SCALARS};
use crate::gpu::words::Word;
use crate::scalar::{ByScalar, SimScalar};
use crate::scenario::{ScalarType, Scenario, builtin};

/// A type over a scalar (an agent group of a model): `Of<S>` is it over `S`.
pub(crate) trait Family {
    type Of<S>;
}

/// The ant groups over each scalar.
pub(crate) struct AntGroups;

impl Family for AntGroups {
    type Of<S> = AntGroup<S>;
}

/// The bee groups over each scalar.
pub(crate) struct BeeGroups;

impl Family for BeeGroups {
    type Of<S> = BeeGroup<S>;
}

/// A value of `G` over either scalar (an `AnyAntGroup`, an `AnyBeeGroup`).
pub(crate) type Any<G> = ByScalar<<G as Family>::Of<f32>, <G as Family>::Of<Fx>>;

/// A scalar of the simulator, as the tests need it.
pub(crate) trait TestScalar: Word + SimScalar {
    /// The scenario's name for it.
    const TYPE: ScalarType;
    /// `g` if it computes in this scalar.
    fn pick<G: Family>(g: &Any<G>) -> Option<&G::Of<Self>>;
}

impl TestScalar for Fx {
    const TYPE: ScalarType = ScalarType::Fixed;
    fn pick<G: Family>(g: &Any<G>) -> Option<&G::Of<Fx>> {
        match g {
            ByScalar::Fixed(g) => Some(g),
            ByScalar::F32(_) => None,
        }
    }
}

impl TestScalar for f32 {
    const TYPE: ScalarType = ScalarType::F32;
    fn pick<G: Family>(g: &Any<G>) -> Option<&G::Of<f32>> {
        match g {
            ByScalar::F32(g) => Some(g),
            ByScalar::Fixed(_) => None,
        }
    }
}

/// A value per scalar, made once (the test GPU and a model's kernels, for every test).
pub(crate) struct PerScalar<T> {
    fx: OnceLock<T>,
    f32: OnceLock<T>,
}

impl<T> PerScalar<T> {
    pub(crate) const fn new() -> Self {
        PerScalar {
            fx: OnceLock::new(),
            f32: OnceLock::new(),
        }
    }

    /// The value for `S`, made by `init` the first time.
    pub(crate) fn get<S: SimScalar>(&self, init: impl FnOnce() -> T) -> &T {
        let cell = match S::KIND {
            ScalarKind::I16F16 => &self.fx,
            ScalarKind::F32 => &self.f32,
        };
        cell.get_or_init(init)
    }
}

/// The built-in scenario `name` over `S`, shortened to `steps` steps (its events at the same
/// fraction of the shortened run).
pub(crate) fn shortened<S: TestScalar>(name: &str, steps: u32) -> Scenario {
    builtin(name)
        .unwrap_or_else(|| panic!("no built-in scenario {name}"))
        .in_scalar(S::TYPE)
        .squeezed(steps)
}

/// The built-in scenario `name` in fixed point, shortened to `steps` steps ([`shortened`]).
pub(crate) fn fixed(name: &str, steps: u32) -> Scenario {
    shortened::<Fx>(name, steps)
}

/// Each agent's parameters, by id `0..agents`: those of its group in `groups` (all over `S`),
/// `of` giving a group's ids and parameters.
pub(crate) fn params_by_id<S: TestScalar, G: Family, P: Copy>(
    agents: usize,
    groups: &[Any<G>],
    of: impl Fn(&G::Of<S>) -> (&[u32], P),
) -> Vec<P> {
    let mut by_id = vec![None; agents];
    for g in groups {
        let g = S::pick::<G>(g).expect("every group in the scalar asked for");
        let (ids, params) = of(g);
        for &id in ids {
            by_id[id as usize] = Some(params);
        }
    }
    by_id.into_iter().map(Option::unwrap).collect()
}

/// The request and the reply of an exchange, decoded from postcard.
pub(crate) fn decode_exchange<Q: DeserializeOwned, R: DeserializeOwned>(ex: &Exchange) -> (Q, R) {
    (
        decode_payload(&ex.request.bytes).unwrap(),
        decode_payload(&ex.reply.bytes).unwrap(),
    )
}

/// `n` of `total` (1 of none).
pub(crate) fn share(n: usize, total: usize) -> f64 {
    if total == 0 {
        1.0
    } else {
        n as f64 / total as f64
    }
}

/// The first of two (differences, say): `first`, or `o` where there is none.
pub(crate) fn keep_first<T>(first: &mut Option<T>, o: Option<T>) {
    if first.is_none() {
        *first = o;
    }
}

/// A first difference, described on a line of its own (nothing if none).
pub(crate) fn first_difference(first: Option<&String>) -> String {
    first.map_or(String::new(), |f| format!("\n  the first difference: {f}"))
}

/// Values compared (frames), and those with every word equal.
#[derive(Clone, Copy, Debug, Default)]
pub(crate) struct Tally {
    pub(crate) total: usize,
    pub(crate) same: usize,
}

impl Tally {
    /// One value, the same or not.
    pub(crate) fn one(same: bool) -> Tally {
        Tally {
            total: 1,
            same: usize::from(same),
        }
    }

    pub(crate) fn add(&mut self, o: Tally) {
        self.total += o.total;
        self.same += o.same;
    }

    /// Those that differ.
    pub(crate) fn differ(&self) -> usize {
        self.total - self.same
    }

    /// The share of those with every word equal (1 of none).
    pub(crate) fn share(&self) -> f64 {
        share(self.same, self.total)
    }
}

/// What a comparison measures besides the counts (`()` for nothing), summed over comparisons.
pub(crate) trait Measure: Default + Debug {
    /// `o` added to `self`.
    fn add(&mut self, o: Self);
}

impl Measure for () {
    fn add(&mut self, (): ()) {}
}

/// How the GPU's answers compare with Rust's.
#[derive(Debug, Default)]
pub(crate) struct Compared<M = ()> {
    /// Decisions compared.
    pub(crate) total: usize,
    /// Those with every output word equal.
    pub(crate) identical: usize,
    /// Those with the same status and, if Ok, the same discrete fields.
    pub(crate) discrete: usize,
    /// Those refused (by Rust).
    pub(crate) refused: usize,
    /// The first that differs: index, Rust's words, the GPU's words.
    pub(crate) first: Option<(usize, Vec<u32>, Vec<u32>)>,
    /// What else is measured.
    pub(crate) measured: M,
}

impl<M: Measure> Compared<M> {
    /// `got` (the GPU's output) against `want` (Rust's), `words` per decision, a status first;
    /// of two that differ, `discrete(got, want)` says whether their discrete fields are the same
    /// (their statuses being) and `measure` measures them.
    pub(crate) fn of(
        got: &[u32],
        want: &[u32],
        words: usize,
        discrete: impl Fn(&[u32], &[u32]) -> bool,
        mut measure: impl FnMut(&mut M, &[u32], &[u32]),
    ) -> Self {
        assert_eq!(got.len(), want.len(), "output length");
        let mut c = Compared::<M>::default();
        for (i, (g, w)) in got.chunks(words).zip(want.chunks(words)).enumerate() {
            c.total += 1;
            c.refused += usize::from(w[0] != 0);
            if g == w {
                c.identical += 1;
                c.discrete += 1;
                continue;
            }
            if g[0] == w[0] && discrete(g, w) {
                c.discrete += 1;
            }
            measure(&mut c.measured, g, w);
            c.first.get_or_insert((i, w.to_vec(), g.to_vec()));
        }
        c
    }

    pub(crate) fn add(&mut self, o: Self) {
        self.total += o.total;
        self.identical += o.identical;
        self.discrete += o.discrete;
        self.refused += o.refused;
        self.measured.add(o.measured);
        keep_first(&mut self.first, o.first);
    }

    /// Panics unless every decision was bit for bit Rust's, with the first that was not (its
    /// input among `cases`, and both answers as `show` describes them).
    pub(crate) fn assert_identical<C: Debug>(
        &self,
        what: &str,
        cases: &[C],
        show: impl Fn(&[u32]) -> String,
    ) {
        if let Some((i, want, got)) = &self.first {
            panic!(
                "{what}: {} of {} decisions differ; the first, #{i}:\n  input {:?}\n  Rust {}\n  GPU  {}",
                self.total - self.identical,
                self.total,
                cases.get(*i),
                show(want),
                show(got),
            );
        }
    }
}

/// Panics unless `kernel`, composed with `modules(scalar)`, is valid WGSL (naga, as wgpu would
/// check it) over every scalar module, `what` naming it.
pub(crate) fn assert_valid_wgsl<const M: usize>(
    what: &str,
    modules: fn(&'static Module) -> [&'static Module; M],
    kernel: &str,
) {
    for scalar in SCALARS {
        shaders::tests::validate(
            &format!("{what} over {}", scalar.name),
            &shaders::compose(&modules(scalar), kernel),
        );
    }
}

/// Panics unless `wgsl` declares every constant of `constants` with its value (`const NAME: u32
/// = 12u;`, or also `= 0xcu;` where `hex`).
pub(crate) fn assert_constants<V: Display + LowerHex>(
    wgsl: &str,
    constants: &[(&str, V)],
    hex: bool,
) {
    for (name, value) in constants {
        let decl = format!("const {name}: u32 = {value}u;");
        let in_hex = format!("const {name}: u32 = {value:#x}u;");
        assert!(
            wgsl.contains(&decl) || (hex && wgsl.contains(&in_hex)),
            "{decl} is not in the shaders"
        );
    }
}

/// A model's status words (`status_of`, `status_error`), as a test checks them.
pub(crate) struct StatusWords {
    /// The WGSL that names the fields, and its file's name.
    pub(crate) wgsl: &'static str,
    pub(crate) file: &'static str,
    /// The prefix of the fields' constants (`ANT`: `ANT_FIELD_STATE_POS`).
    pub(crate) prefix: &'static str,
    /// The fields by code (0 is no field, nor is an empty name).
    pub(crate) fields: &'static [&'static str],
    /// The kinds of error the kernels write (the first of `NonFinite`, `OutOfRange`,
    /// `Inconsistent`).
    pub(crate) kinds: usize,
    /// The indices tried.
    pub(crate) indices: [Option<u16>; 3],
    pub(crate) status_of: fn(&swarm_core::Error) -> u32,
    pub(crate) status_error: fn(u32) -> crate::Result<Result<(), swarm_core::Error>>,
}

impl StatusWords {
    /// Panics unless the WGSL names every field with its code (`const ANT_FIELD_STATE_POS: u32 =
    /// 1u; // "state.pos"`), every error of each kind, field and index decodes to itself, 0 to
    /// Ok, a field code past the table and the kind after the last are refused, and an error no
    /// controller returns has no status word (`u32::MAX`).
    pub(crate) fn check(&self) {
        use swarm_core::Error;
        let (status_of, status_error) = (self.status_of, self.status_error);
        for (code, &field) in self.fields.iter().enumerate().skip(1) {
            if field.is_empty() {
                continue; // a code the model does not use
            }
            let name = field.replace('.', "_").to_uppercase();
            let decl = format!(
                "const {}_FIELD_{name}: u32 = {code}u; // \"{field}\"",
                self.prefix
            );
            assert!(self.wgsl.contains(&decl), "{decl} is not in {}", self.file);
            for index in self.indices {
                let errors = [
                    Error::NonFinite { field, index },
                    Error::OutOfRange { field, index },
                    Error::Inconsistent { field, index },
                ];
                for e in errors.into_iter().take(self.kinds) {
                    assert_eq!(status_error(status_of(&e)).unwrap(), Err(e));
                }
            }
        }
        assert_eq!(status_error(0).unwrap(), Ok(()));
        assert!(status_error(0x0000_ff01).is_err());
        assert!(status_error(0x0000_0101 + self.kinds as u32).is_err());
        assert_eq!(status_of(&Error::Payload), u32::MAX);
    }
}
