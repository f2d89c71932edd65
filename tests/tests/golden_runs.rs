//! Every built-in scenario, in both scalars, produces exactly the recorded bytes: the hashes of
//! its `positions.npy` and `summary.json` (the summary without its wall-clock fields: run time,
//! rate and thread count) are pinned below.
//!
//! These pins hold the behaviour still while the engine is refactored (issue 13): a refactor
//! changes no bit. A change that is *meant* to change the behaviour of a model updates them:
//! run `GOLDEN_PRINT=1 cargo test --release -p swarm-tests --test golden_runs -- --nocapture`
//! and paste the printed table, saying in the commit why the runs changed.

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
        0xe26ed3dbb23c7cf3,
    ),
    (
        "bees-fig11-grassland",
        "fixed",
        0xb947fb53cb3c5f00,
        0x6dd29240aebd6af1,
    ),
    (
        "bees-fig15-nest",
        "f32",
        0x91077df04fe08408,
        0xded6f9aed3f8cbf6,
    ),
    (
        "bees-fig15-nest",
        "fixed",
        0x790386d5d0da2f50,
        0x65ce4e59620c49e9,
    ),
    (
        "bees-fig14-shafts",
        "f32",
        0x17b9f4f984e68400,
        0x76a66de4d82592ff,
    ),
    (
        "bees-fig14-shafts",
        "fixed",
        0x084204fd380b454f,
        0xda9d258703e03517,
    ),
    (
        "wang-fig6-two-blocks",
        "f32",
        0xcda5505c19608603,
        0x7ac6ed7f68325e6a,
    ),
    (
        "wang-fig6-two-blocks",
        "fixed",
        0x386178b007176f1e,
        0xadc55ebe2c34f995,
    ),
    (
        "wang-fig7-min-cost",
        "f32",
        0x21d9fdc684a713ce,
        0x953d2363f12f3288,
    ),
    (
        "wang-fig7-min-cost",
        "fixed",
        0x68f1713abee834ee,
        0x03c717c4f0b05693,
    ),
    (
        "wang-fig8-chasing",
        "f32",
        0x38bede9b091f6bb9,
        0x7713d97028c77622,
    ),
    (
        "wang-fig8-chasing",
        "fixed",
        0xeffb4600b5e5ef82,
        0x55beb610283a723e,
    ),
    (
        "wang-fig9-aggregation",
        "f32",
        0xf557cf9f7b2dc632,
        0x47af054b2cfbd731,
    ),
    (
        "wang-fig9-aggregation",
        "fixed",
        0x0400c90ac7a5e8ed,
        0x11fbac8a76ebec9b,
    ),
    (
        "wang-fig10-phototaxis",
        "f32",
        0x673e9c0db2ce309b,
        0x16d10c842eccf770,
    ),
    (
        "wang-fig10-phototaxis",
        "fixed",
        0xa21ba3679fea0fa8,
        0xd53a61b83e6839cd,
    ),
    (
        "wang-fig1a-locusts",
        "f32",
        0x708987bb629f7112,
        0xe905c41920a481d4,
    ),
    (
        "wang-fig1a-locusts",
        "fixed",
        0xbb127f0f0ff270c1,
        0xc1b1cbfe42a48411,
    ),
    (
        "wang-fig13-noise-compare",
        "f32",
        0x8eedaf16e4fd2505,
        0x1700ef255718636c,
    ),
    (
        "wang-fig13-noise-compare",
        "fixed",
        0xbebb441ddda518a5,
        0x6996358bf032572f,
    ),
    (
        "fly-fig1-midges",
        "f32",
        0x2f26de828543cd5a,
        0x2de73f4905c1abf8,
    ),
    (
        "fly-fig1-midges",
        "fixed",
        0x3fb18410fdee81de,
        0xe6cdbfd23660d228,
    ),
    (
        "fly-fig2-fruitfly",
        "f32",
        0x0e32e2307d51e92b,
        0x7707ee61a6c211c1,
    ),
    (
        "fly-fig2-fruitfly",
        "fixed",
        0x7bb6fbd3ecfe7614,
        0x042fc0000d804cd7,
    ),
    (
        "fly-fig3-aggregation",
        "f32",
        0x36a1c73df8394605,
        0x68b32119e4dc9307,
    ),
    (
        "fly-fig3-aggregation",
        "fixed",
        0x08e5c4b7c38f897e,
        0x78faac449570bf90,
    ),
    (
        "fly-fig3-aggregation-3000",
        "f32",
        0xc2650c51c3d00d0d,
        0x4ea8e54364db752d,
    ),
    (
        "fly-fig3-aggregation-3000",
        "fixed",
        0xdabf1b997fabbb5f,
        0x6e9090fedcc52b07,
    ),
    (
        "fly-fig4-locusts",
        "f32",
        0xd87b282216cc16d7,
        0x1039a87ce2c3657f,
    ),
    (
        "fly-fig4-locusts",
        "fixed",
        0x92028b157ba9511e,
        0x52f580effa250b10,
    ),
    (
        "fly-fig5-mating",
        "f32",
        0x0fb058f9030618b8,
        0xfd523199d1f08d8a,
    ),
    (
        "fly-fig5-mating",
        "fixed",
        0x2533000114867381,
        0xceb91ab46949bc8e,
    ),
    (
        "fly-fig6-phase",
        "f32",
        0xd1944abfb5cfe56d,
        0x127a3b22665ddc0c,
    ),
    (
        "fly-fig6-phase",
        "fixed",
        0xb0e19d4cbb7bfca7,
        0xee1714b84fb952ec,
    ),
    (
        "fly-fig7-phototaxis",
        "f32",
        0x183af4cd4c32137f,
        0x5858770e088ec5b0,
    ),
    (
        "fly-fig7-phototaxis",
        "fixed",
        0x205667241202d424,
        0x4419696ca8809833,
    ),
    (
        "fly-fig8-escape",
        "f32",
        0xdb0218341c59f499,
        0x0a8d72ed971456ab,
    ),
    (
        "fly-fig8-escape",
        "fixed",
        0xf871b9f98ca3dfb2,
        0x795cb6fb488cd141,
    ),
    (
        "fly-fig9-bats",
        "f32",
        0x5358a48c98ae4084,
        0x189832e759553177,
    ),
    (
        "fly-fig9-bats",
        "fixed",
        0x282b27b2956783e4,
        0x7c573f730e31104e,
    ),
    (
        "li-fig4-confined",
        "f32",
        0x2d7b66910bb8a45f,
        0x7a1fc0c072638539,
    ),
    (
        "li-fig4-confined",
        "fixed",
        0x0ada91c8123d8519,
        0xa20655e75499d3ea,
    ),
    (
        "li-fig5-lantern",
        "f32",
        0x5c4948232ebd8ffc,
        0x3c0c4bd768d02485,
    ),
    (
        "li-fig5-lantern",
        "fixed",
        0x53b7f4e44da7bb8b,
        0xadfbcefbc09a1b8f,
    ),
    (
        "li-fig8-9-cells",
        "f32",
        0x65f4e6499be3959a,
        0x264ccd942b2c6f47,
    ),
    (
        "li-fig8-9-cells",
        "fixed",
        0x4a6bff9e62224b79,
        0xf7c9b9db0d0079da,
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
    let mut table = String::new();
    let mut wrong = Vec::new();
    for &name in scenario::builtin_names() {
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
