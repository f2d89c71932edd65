//! Every built-in scenario, in both scalars, produces exactly the recorded bytes: the hashes of
//! its `positions.npy` and `summary.json` (the summary without its wall-clock fields: run time,
//! rate and thread count) are pinned below.
//!
//! These pins hold the behaviour still while the engine is refactored (issue 13): a refactor
//! changes no bit. A change that is *meant* to change the behaviour of a model updates them:
//! run `GOLDEN_PRINT=1 cargo test --release -p swarm-tests --test golden_runs -- --nocapture`
//! and paste the printed table, saying in the commit why the runs changed. A new scenario's
//! pins alone: `GOLDEN_ONLY=name GOLDEN_PRINT=1 ...` (the rows to add).

use std::path::Path;

use swarm_core::wire::fnv1a64;
use swarm_sim::run::{RunOptions, run};
use swarm_sim::scenario::{self, ScalarType};

/// Ticks per run: long enough for trails, gathering and the first events (longer scenario
/// events are covered by the behaviour tests), short enough for CI.
const STEPS: u32 = 600;

/// (scenario, scalar, FNV-1a 64 of positions.npy, of the normalised summary.json).
const PINNED: &[(&str, &str, u64, u64)] = &[
    (
        "ants-fig7a-single-colony",
        "f32",
        0x863bc5094fc623c8,
        0x1545fad23738791c,
    ),
    (
        "ants-fig7a-single-colony",
        "fixed",
        0x0cd507256ab51af0,
        0x48792b43c9f90d3a,
    ),
    (
        "ants-fig7b-obstacles",
        "f32",
        0xf4bc2278a148493f,
        0x318b4217ffb5c8eb,
    ),
    (
        "ants-fig7b-obstacles",
        "fixed",
        0xba506b95ee9cdfeb,
        0x2109a63044cce655,
    ),
    (
        "ants-fig8a-hybrid",
        "f32",
        0xcf05526c6ec62e2e,
        0x5adffd6bedada3de,
    ),
    (
        "ants-fig8a-hybrid",
        "fixed",
        0x530f57eb18f99248,
        0x961ea8c395e100b1,
    ),
    (
        "ants-fig8b-hybrid-obstacles",
        "f32",
        0x344c1267f5db564e,
        0x9753ec147251d357,
    ),
    (
        "ants-fig8b-hybrid-obstacles",
        "fixed",
        0x09c4206ee8eb16fe,
        0xed2ebced32231086,
    ),
    (
        "ants-fig11-dynamic-obstacles",
        "f32",
        0x6b946b43cdb4829e,
        0xe749a491e592a2aa,
    ),
    (
        "ants-fig11-dynamic-obstacles",
        "fixed",
        0x3fa1f74092bb3e25,
        0x1dd7ddff412ce7e4,
    ),
    (
        "ants-fig12-moved-food",
        "f32",
        0xd6f7053ec320e38a,
        0x547d03ef22ba94c2,
    ),
    (
        "ants-fig12-moved-food",
        "fixed",
        0x8305cb1221961892,
        0xef9534a0b38f40d6,
    ),
    (
        "ants-fig13-disturbance",
        "f32",
        0x3e9e9dcc24c74f7e,
        0xb220afa547ca25c9,
    ),
    (
        "ants-fig13-disturbance",
        "fixed",
        0x3030e676c0a48526,
        0x0a52dafc74a3301b,
    ),
    (
        "ants-fig1c-heart",
        "f32",
        0x3833c61a8a575a07,
        0x7ee202e2c91cc74d,
    ),
    (
        "ants-fig1c-heart",
        "fixed",
        0xffa2f29779987cd1,
        0xfce581a8fdbdab90,
    ),
    (
        "ants-fig14-waypoints",
        "f32",
        0x3fa2e1eb6be65633,
        0x89bbfeb2a7375c83,
    ),
    (
        "ants-fig14-waypoints",
        "fixed",
        0x1c5dbcddb9e4b93b,
        0x6ad2a646c47ba2e4,
    ),
    (
        "bees-fig11-grassland",
        "f32",
        0x198f3c2103455884,
        0xa3c9535123f71d84,
    ),
    (
        "bees-fig11-grassland",
        "fixed",
        0xb947fb53cb3c5f00,
        0x767f958e1a55c1d8,
    ),
    (
        "bees-fig15-nest",
        "f32",
        0x91077df04fe08408,
        0x09d821d4c5c5e238,
    ),
    (
        "bees-fig15-nest",
        "fixed",
        0x790386d5d0da2f50,
        0x0698459b833b6895,
    ),
    (
        "bees-fig14-shafts",
        "f32",
        0x17b9f4f984e68400,
        0xfb19c6ac4e3ac3e8,
    ),
    (
        "bees-fig14-shafts",
        "fixed",
        0x084204fd380b454f,
        0xa8166597b405beca,
    ),
    (
        "wang-fig6-two-blocks",
        "f32",
        0xcda5505c19608603,
        0xeac1b4e83c39d3b2,
    ),
    (
        "wang-fig6-two-blocks",
        "fixed",
        0x386178b007176f1e,
        0x4836ad45d66f402d,
    ),
    (
        "wang-fig7-min-cost",
        "f32",
        0x21d9fdc684a713ce,
        0x623bbb52923b7908,
    ),
    (
        "wang-fig7-min-cost",
        "fixed",
        0x68f1713abee834ee,
        0xbd73af3c9be6baa3,
    ),
    (
        "wang-fig8-chasing",
        "f32",
        0x38bede9b091f6bb9,
        0x574b069844f35138,
    ),
    (
        "wang-fig8-chasing",
        "fixed",
        0xeffb4600b5e5ef82,
        0x02b8d3b184c7d0a4,
    ),
    (
        "wang-fig9-aggregation",
        "f32",
        0xf557cf9f7b2dc632,
        0x2ff5ea849762b875,
    ),
    (
        "wang-fig9-aggregation",
        "fixed",
        0x0400c90ac7a5e8ed,
        0x766c0bf539b30a59,
    ),
    (
        "wang-fig10-phototaxis",
        "f32",
        0x673e9c0db2ce309b,
        0xc65607fba4133a8a,
    ),
    (
        "wang-fig10-phototaxis",
        "fixed",
        0xa21ba3679fea0fa8,
        0x798031d4ef9bc6d5,
    ),
    (
        "wang-fig1a-locusts",
        "f32",
        0x708987bb629f7112,
        0x301774dc828edab2,
    ),
    (
        "wang-fig1a-locusts",
        "fixed",
        0xbb127f0f0ff270c1,
        0x07b1ce84fcbd2b37,
    ),
    (
        "wang-fig13-noise-compare",
        "f32",
        0x8eedaf16e4fd2505,
        0x4be2ca7559809eb2,
    ),
    (
        "wang-fig13-noise-compare",
        "fixed",
        0xbebb441ddda518a5,
        0xdc862527802412d9,
    ),
    (
        "fly-fig1-midges",
        "f32",
        0x2f26de828543cd5a,
        0x48d8a5992433e57f,
    ),
    (
        "fly-fig1-midges",
        "fixed",
        0x3fb18410fdee81de,
        0xaf3947ce345216b9,
    ),
    (
        "fly-fig2-fruitfly",
        "f32",
        0x0e32e2307d51e92b,
        0x16a3d12370202e30,
    ),
    (
        "fly-fig2-fruitfly",
        "fixed",
        0x7bb6fbd3ecfe7614,
        0x44c8253c2ff81200,
    ),
    (
        "fly-fig3-aggregation",
        "f32",
        0x36a1c73df8394605,
        0x36ea38ef0e627840,
    ),
    (
        "fly-fig3-aggregation",
        "fixed",
        0x08e5c4b7c38f897e,
        0x18a73279d1af4ff9,
    ),
    (
        "fly-fig3-aggregation-3000",
        "f32",
        0xc2650c51c3d00d0d,
        0xdccf9dd820d72b68,
    ),
    (
        "fly-fig3-aggregation-3000",
        "fixed",
        0xdabf1b997fabbb5f,
        0x28c199535c412faa,
    ),
    (
        "fly-fig4-locusts",
        "f32",
        0xd87b282216cc16d7,
        0x3253632ba8921f9c,
    ),
    (
        "fly-fig4-locusts",
        "fixed",
        0x92028b157ba9511e,
        0xd1411626e40cdff9,
    ),
    (
        "fly-fig5-mating",
        "f32",
        0x0fb058f9030618b8,
        0xce0b6eb7eb6708b3,
    ),
    (
        "fly-fig5-mating",
        "fixed",
        0x2533000114867381,
        0xfb36e783456316cf,
    ),
    (
        "fly-fig6-phase",
        "f32",
        0xd1944abfb5cfe56d,
        0xc86d11ed6e4a45e7,
    ),
    (
        "fly-fig6-phase",
        "fixed",
        0xb0e19d4cbb7bfca7,
        0x47bbaa439322b77b,
    ),
    (
        "fly-fig7-phototaxis",
        "f32",
        0x183af4cd4c32137f,
        0x6641781d0c672cc1,
    ),
    (
        "fly-fig7-phototaxis",
        "fixed",
        0x205667241202d424,
        0x310cb0f88c6f87c0,
    ),
    (
        "fly-fig8-escape",
        "f32",
        0xdb0218341c59f499,
        0xc5261a476c8061ec,
    ),
    (
        "fly-fig8-escape",
        "fixed",
        0xf871b9f98ca3dfb2,
        0xd125f070e87da28a,
    ),
    (
        "fly-fig9-bats",
        "f32",
        0x5358a48c98ae4084,
        0xf30d51b69b708f5e,
    ),
    (
        "fly-fig9-bats",
        "fixed",
        0x282b27b2956783e4,
        0xb216bb44537e97ff,
    ),
    (
        "li-fig4-confined",
        "f32",
        0x2d7b66910bb8a45f,
        0x043ace04f8befdda,
    ),
    (
        "li-fig4-confined",
        "fixed",
        0x0ada91c8123d8519,
        0x4dfe1a177f3f561e,
    ),
    (
        "li-fig5-lantern",
        "f32",
        0x5c4948232ebd8ffc,
        0x88e90b5e5505d8f6,
    ),
    (
        "li-fig5-lantern",
        "fixed",
        0x53b7f4e44da7bb8b,
        0x47a8441116e1c5b9,
    ),
    (
        "li-fig5-butterflies",
        "f32",
        0x1240080bbac105d3,
        0x411e29b306fd5b51,
    ),
    (
        "li-fig5-butterflies",
        "fixed",
        0x70ce780a478d5474,
        0xc6dc488df9d91e83,
    ),
    (
        "li-fig6-lights",
        "f32",
        0x82ec13bc1a04a7d8,
        0x7a939a009f06ef04,
    ),
    (
        "li-fig6-lights",
        "fixed",
        0x325796c0779694bd,
        0x27445e382c4e382a,
    ),
    (
        "li-fig8-9-cells",
        "f32",
        0x65f4e6499be3959a,
        0x7d68ab9363750c73,
    ),
    (
        "li-fig8-9-cells",
        "fixed",
        0x4a6bff9e62224b79,
        0x0b23eed4a1414d21,
    ),
];

/// The summary without what depends on the machine and the moment.
fn normalised_summary(path: &Path) -> Vec<u8> {
    let text = std::fs::read_to_string(path).expect("summary.json");
    let mut v: serde_json::Value = serde_json::from_str(&text).expect("summary is JSON");
    let obj = v.as_object_mut().expect("summary is an object");
    for k in ["wall_seconds", "agent_steps_per_s", "threads"] {
        obj.remove(k);
    }
    serde_json::to_vec(&v).expect("serialise")
}

fn hashes(name: &str, scalar: ScalarType) -> (u64, u64) {
    let mut sc = scenario::builtin(name).expect("built-in");
    for g in &mut sc.groups {
        g.scalar = scalar;
    }
    sc.outputs.render = false;
    sc.outputs.gif = false;
    sc.outputs.trajectories = false;
    let dir = tempfile::tempdir().expect("temp dir");
    let out = dir.path().join("run");
    let opts = RunOptions {
        out: out.clone(),
        steps: Some(STEPS.min(sc.steps)),
        seed: None,
        threads: Some(2),
        backend: None,
        progress: false,
        warnings: Vec::new(),
    };
    run(&sc, &opts).unwrap_or_else(|e| panic!("{name}: {e}"));
    let npy = std::fs::read(out.join("positions.npy")).expect("positions.npy");
    (
        fnv1a64(&npy),
        fnv1a64(&normalised_summary(&out.join("summary.json"))),
    )
}

#[test]
fn every_built_in_scenario_produces_the_pinned_bytes_in_both_scalars() {
    let print = std::env::var_os("GOLDEN_PRINT").is_some();
    // GOLDEN_ONLY=a,b: only those scenarios (to print the pins of new ones quickly).
    let only = std::env::var("GOLDEN_ONLY").ok();
    let chosen = |name: &str| {
        only.as_deref()
            .is_none_or(|o| o.split(',').any(|n| n == name))
    };
    for name in only.iter().flat_map(|o| o.split(',')) {
        assert!(
            scenario::builtin_names().contains(&name),
            "GOLDEN_ONLY: no built-in scenario {name:?}"
        );
    }
    let mut table = String::new();
    let mut wrong = Vec::new();
    for &name in scenario::builtin_names().iter().filter(|n| chosen(n)) {
        for (scalar, tag) in [(ScalarType::F32, "f32"), (ScalarType::Fixed, "fixed")] {
            let (npy, summary) = hashes(name, scalar);
            table.push_str(&format!(
                "    (\"{name}\", \"{tag}\", {npy:#018x}, {summary:#018x}),\n"
            ));
            let pinned = PINNED.iter().find(|p| p.0 == name && p.1 == tag);
            match pinned {
                Some(&(_, _, n, s)) if n == npy && s == summary => {}
                Some(&(_, _, n, s)) => wrong.push(format!(
                    "{name} ({tag}): positions.npy {npy:#018x} (pinned {n:#018x}), \
                     summary.json {summary:#018x} (pinned {s:#018x})"
                )),
                None => wrong.push(format!("{name} ({tag}): not pinned")),
            }
        }
    }
    if print {
        println!("const PINNED: &[(&str, &str, u64, u64)] = &[\n{table}];");
    }
    assert!(
        wrong.is_empty(),
        "runs differ from the pinned bytes:\n  {}\n(if the change is meant, see this file's docs)",
        wrong.join("\n  ")
    );
}
