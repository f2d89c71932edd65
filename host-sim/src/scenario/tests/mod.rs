//! Tests of the scenario layer: the built-ins, every kind of error (file, line, field), round
//! trips.

use std::path::Path;

use swarm_core::ant::AntParams;
use swarm_core::bee::BeeParams;
use swarm_core::model::ParamValue;

use super::*;
use crate::SimError;
use crate::ants::AntParamsOverride;
use crate::bees::{BeeParamsOverride, BeePreset, bee_params};

mod sanity;

/// A small valid ant scenario; the error tests break one thing at a time.
const ANTS: &str = include_str!("ants.toml");

/// A small valid bee scenario.
const BEES: &str = include_str!("bees.toml");

const FILE: &str = "tests/broken.toml";

/// 1-based line of the first occurrence of `needle` in `text`.
fn line_of(text: &str, needle: &str) -> usize {
    let at = text
        .find(needle)
        .unwrap_or_else(|| panic!("`{needle}` not in the text"));
    text[..at].matches('\n').count() + 1
}

/// `text` with the first `from` replaced by `to` (which must exist).
fn edit(text: &str, from: &str, to: &str) -> String {
    assert!(text.contains(from), "`{from}` not in the text");
    text.replacen(from, to, 1)
}

/// Loads `text`, expects a diagnostic and checks its file, line, field and that the message
/// (and the displayed error) contain `says`.
#[track_caller]
fn expect_error(text: &str, line: usize, field: &str, says: &str) -> Diagnostic {
    let err = Scenario::from_str(text, FILE).expect_err("the scenario should be rejected");
    let shown = err.to_string();
    let d = err.diagnostic().expect("a diagnostic").clone();
    assert_eq!(d.file, FILE, "{shown}");
    assert_eq!(d.line, Some(line), "{shown}");
    assert_eq!(d.field, field, "{shown}");
    assert!(
        d.message.contains(says),
        "message should contain `{says}`: {shown}"
    );
    assert!(shown.contains(&format!("{FILE}:{line}:")), "{shown}");
    if !field.is_empty() {
        assert!(shown.contains(&format!("`{field}`")), "{shown}");
    }
    d
}

/// `base` with the first `from` replaced by `to` ([`edit`]) is refused at the line of `at` in
/// the edited text, naming `field`, with a message containing `says` ([`expect_error`]).
#[track_caller]
fn rejects(base: &str, from: &str, to: &str, at: &str, field: &str, says: &str) -> Diagnostic {
    refused_at(&edit(base, from, to), at, field, says)
}

/// [`expect_error`] at the line of the first `at` in `text`.
#[track_caller]
fn refused_at(text: &str, at: &str, field: &str, says: &str) -> Diagnostic {
    expect_error(text, line_of(text, at), field, says)
}

#[test]
fn the_test_scenarios_are_valid() {
    let s = Scenario::from_str(ANTS, "x/test.toml").unwrap();
    assert_eq!(s.name, "test");
    assert_eq!(
        s.world,
        World::Plane {
            min: [0.0, 0.0],
            max: [100.0, 50.0]
        }
    );
    assert_eq!(s.groups.len(), 2);
    assert_eq!(s.groups[0].scalar, ScalarType::F32);
    assert_eq!(
        s.events[2].action,
        Action::Move {
            object: "food".into(),
            to: vec![80.0, 30.0]
        }
    );
    assert_eq!(s.outputs, Outputs::default());
    let b = Scenario::from_str(BEES, "dir/bees-small.toml").unwrap();
    assert_eq!(b.name, "bees-small", "the name defaults to the file stem");
    assert_eq!(bee_params(&b.groups[0]).unwrap().kappa2, 3.0);
    assert_eq!(
        bee_params(&b.groups[0]).unwrap().kappa1,
        BeeParams::<f32>::around_nest().kappa1
    );
}

#[test]
fn every_builtin_loads() {
    assert_eq!(builtin_names().len(), BUILTINS.len());
    for b in BUILTINS {
        let s = builtin(b.name).unwrap_or_else(|| {
            let err = resolve(b.name).expect_err("a built-in that does not load");
            panic!("built-in `{}` does not load: {err}", b.name)
        });
        assert_eq!(s.name, b.name, "a built-in's name is its file stem");
        for (needle, why) in [("Fig.", "cite the figure"), ("--steps", "mention --steps")] {
            assert!(s.description.contains(needle), "{}: {why}", b.name);
        }
        assert!(!b.summary.is_empty() && !b.summary.contains('\n'));
        let model = &s.groups[0].model;
        assert!(s.groups.iter().all(|g| g.model == *model));
        let (prefix, range) = if *model == Model::new("ant") {
            ("ants-", 3000..=6000)
        } else if *model == Model::new("bee") {
            ("bees-", 1000..=2000)
        } else if *model == Model::new("fly") {
            ("fly-", 1000..=10000)
        } else if *model == Model::new("li") {
            // Fig. 4's accumulated density: 200 s at 100 steps/s.
            ("li-", 1000..=20000)
        } else {
            ("wang-", 1000..=10000)
        };
        assert!(b.name.starts_with(prefix));
        assert!(range.contains(&s.steps), "{}: {} steps", b.name, s.steps);
    }
    assert!(builtin("no-such-scenario").is_none());
}

#[test]
fn every_file_in_scenarios_is_a_builtin() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("../scenarios");
    let mut stems: Vec<String> = std::fs::read_dir(&dir)
        .unwrap()
        .filter_map(|e| {
            let p = e.unwrap().path();
            (p.extension()? == "toml").then(|| p.file_stem().unwrap().to_string_lossy().into())
        })
        .collect();
    stems.sort();
    let mut names: Vec<String> = builtin_names().iter().map(|n| n.to_string()).collect();
    names.sort();
    assert_eq!(stems, names);
    // And the files on disk load through `from_path` and `resolve(path)` too.
    for stem in &stems {
        let path = dir.join(format!("{stem}.toml"));
        let s = Scenario::from_path(&path).unwrap();
        assert_eq!(s.source.as_deref(), Some(path.as_path()));
        let r = resolve(path.to_str().unwrap()).unwrap();
        assert_eq!(r, s);
    }
}

#[test]
fn builtins_say_what_the_figures_show() {
    let get = |n: &str| builtin(n).unwrap();
    // How many objects of `kind`, and events of `verb`, a scenario has.
    let objects =
        |s: &Scenario, kind: &str| s.objects.iter().filter(|o| o.kind.tag() == kind).count();
    let events =
        |s: &Scenario, verb: &str| s.events.iter().filter(|e| e.action.verb() == verb).count();
    let fig7a = get("ants-fig7a-single-colony");
    assert_eq!(fig7a.agent_count(), 500);
    let (nest, food) = (fig7a.object("nest").unwrap(), fig7a.object("food").unwrap());
    let (n, f) = (nest.kind.point().unwrap(), food.kind.point().unwrap());
    let d = ((n[0] - f[0]).powi(2) + (n[1] - f[1]).powi(2)).sqrt();
    assert!((90.0..=110.0).contains(&d), "nest-food distance {d}");

    let fig8a = get("ants-fig8a-hybrid");
    assert_eq!(fig8a.agent_count(), 500);
    assert!(fig8a.groups.len() >= 2);
    let nests: std::collections::HashSet<_> = fig8a.groups.iter().map(|g| g.nest.clone()).collect();
    assert_eq!(nests.len(), fig8a.groups.len(), "one nest per colony");

    let fig11 = get("ants-fig11-dynamic-obstacles");
    assert_eq!((events(&fig11, "add"), events(&fig11, "remove")), (3, 3));
    let fig12 = get("ants-fig12-moved-food");
    assert!(
        fig12
            .events
            .iter()
            .any(|e| matches!(&e.action, Action::Move { object, .. } if object == "food"))
    );
    let fig13 = get("ants-fig13-disturbance");
    let verbs: Vec<_> = fig13.events.iter().map(|e| e.action.verb()).collect();
    assert_eq!(verbs, ["start", "stop"]);
    let fig14 = get("ants-fig14-waypoints");
    assert!(objects(&fig14, "waypoint") >= 2);

    let grass = get("bees-fig11-grassland");
    assert_eq!(grass.agent_count(), 1000);
    assert_eq!(
        bee_params(&grass.groups[0]).unwrap(),
        BeeParams::grassland()
    );
    let nest = get("bees-fig15-nest");
    assert_eq!(nest.agent_count(), 350);
    assert_eq!(
        bee_params(&nest.groups[0]).unwrap(),
        BeeParams::around_nest()
    );
    assert_eq!(nest.groups[0].goal.as_deref(), Some("nest"));
    let shafts = get("bees-fig14-shafts");
    assert!(objects(&shafts, "shaft") >= 3);
    assert!(shafts.groups[0].goal.is_some());
}

#[test]
fn round_trip_through_toml() {
    let mut texts: Vec<(String, &str)> = BUILTINS
        .iter()
        .map(|b| (b.name.to_owned(), b.text))
        .collect();
    texts.push(("test".into(), ANTS));
    texts.push(("bees-small".into(), BEES));
    for (name, text) in texts {
        let s = Scenario::from_str(text, &format!("{name}.toml")).unwrap();
        let written = s.to_toml().unwrap();
        let again = Scenario::from_str(&written, "written.toml")
            .unwrap_or_else(|e| panic!("{name}: written TOML does not load: {e}\n{written}"));
        assert_eq!(again, s, "{name}");
        // Serde directly (no file): the same.
        let via_serde: Scenario = toml::from_str(&written).unwrap();
        assert_eq!(via_serde, s, "{name}");
    }
}

#[test]
fn serde_deserialization_validates_too() {
    let err = toml::from_str::<Scenario>(&edit(ANTS, "count = 20", "count = 0")).unwrap_err();
    assert!(err.message().contains("groups[0].count"), "{err}");
    let o: Object =
        toml::from_str("name = \"r\"\nkind = \"rock\"\ncenter = [1, 2]\nradius = 3\n").unwrap();
    assert_eq!(
        o.kind,
        ObjectKind::Rock {
            center: [1.0, 2.0],
            radius: 3.0
        }
    );
    assert!(o.active);
}

#[test]
fn syntax_error_names_file_and_line() {
    let d = rejects(
        ANTS,
        "[[objects]]\nname = \"food\"",
        "[[objects]\nname = \"food\"",
        "[[objects]\n",
        "objects[1]",
        "expected `]`",
    );
    assert_eq!(d.kind, DiagnosticKind::Syntax);
    assert!(d.column.is_some());
    let d = rejects(
        ANTS,
        "count = 20",
        "count = 20 20",
        "count = 20 20",
        "groups[0].count",
        "",
    );
    assert_eq!(d.kind, DiagnosticKind::Syntax);
}

#[test]
fn type_errors_name_the_field() {
    let d = rejects(
        ANTS,
        "count = 20",
        "count = \"many\"",
        "\"many\"",
        "groups[0].count",
        "u32",
    );
    assert_eq!(d.kind, DiagnosticKind::Shape);
    assert_eq!(d.column, Some(9));
    rejects(
        ANTS,
        "spawn = { at = \"nest\", radius = 5 }",
        "spawn = { at = \"nest\", radius = true }",
        "radius = true",
        "groups[0].spawn.radius",
        "f32",
    );
    rejects(
        ANTS,
        "kind = \"rock\"",
        "kind = \"rok\"",
        "\"rok\"",
        "objects[2].kind",
        "unknown variant `rok`",
    );
    rejects(
        ANTS,
        "model = \"ant\"",
        "model = \"wasp\"",
        "\"wasp\"",
        "groups[0].model",
        "`bee`",
    );
    rejects(
        ANTS,
        "count = 10",
        "count = -10",
        "-10",
        "groups[1].count",
        "",
    );
}

#[test]
fn unknown_fields_are_rejected_by_name() {
    rejects(
        ANTS,
        "radius = 5 }",
        "radius = 5, heding = [1, 0] }",
        "heding",
        "groups[0].spawn.heding",
        "`heding`",
    );
    rejects(
        ANTS,
        "steps = 100",
        "steps = 100\nsteeps = 3",
        "steeps",
        "steeps",
        "unknown field `steeps`",
    );
    rejects(
        ANTS,
        "nest = \"nest\"",
        "nest = \"nest\"\nant = { sped = 2 }",
        "sped",
        "groups[0].ant.sped",
        "`sped`",
    );
    // A field of another kind of object.
    rejects(
        ANTS,
        "radius = 4\n",
        "radius = 4\namount = 10\n",
        "amount = 10",
        "objects[2].amount",
        "`rock` has no field `amount`",
    );
}

#[test]
fn missing_fields_point_at_their_table() {
    let text = edit(ANTS, "steps = 100\n", "");
    let d = expect_error(&text, 1, "steps", "missing field `steps`");
    assert!(d.message.contains("expected the number of steps"));
    let text = edit(ANTS, "count = 10\n", "");
    let groups = text.match_indices("[[groups]]").nth(1).unwrap().0;
    let line = text[..groups].matches('\n').count() + 1;
    expect_error(&text, line, "groups[1].count", "missing field `count`");
    let text = edit(ANTS, "center = [50, 25]\n", "");
    expect_error(
        &text,
        line_of(&text, "name = \"rock\"") - 1,
        "objects[2]",
        "missing field `center`",
    );
    rejects(
        ANTS,
        "spawn = { at = \"nest\", radius = 5 }",
        "spawn = { at = \"nest\" }",
        "spawn = { at",
        "groups[0].spawn",
        "missing field `radius`",
    );
}

#[test]
fn world_rules() {
    rejects(
        ANTS,
        "max = [100, 50]",
        "max = [100, -50]",
        "world =",
        "world.max",
        "on y max -50 <= min 0",
    );
    rejects(
        ANTS,
        "dim = 2",
        "dim = 4",
        "world =",
        "world.dim",
        "expected 2 (ants",
    );
    rejects(
        ANTS,
        "min = [0, 0], max",
        "min = [0, 0, 0], max",
        "world =",
        "world.min",
        "expected 2 numbers",
    );
    rejects(
        ANTS,
        "steps = 100",
        "steps = 0",
        "steps = 0",
        "steps",
        "at least 1",
    );
    let text = format!("{ANTS}\n[outputs]\nevery = 0\n");
    refused_at(&text, "every = 0", "outputs.every", "at least 1");
}

#[test]
fn group_rules() {
    // No group at all.
    let start = ANTS.find("[[groups]]").unwrap();
    let end = ANTS.find("[[objects]]").unwrap();
    let text = format!("{}{}", &ANTS[..start], &ANTS[end..]);
    expect_error(&text, 1, "groups", "at least one group");
    rejects(
        ANTS,
        "count = 20",
        "count = 0",
        "count = 0",
        "groups[0].count",
        "1 to 10000000",
    );
    rejects(
        ANTS,
        "count = 20",
        "count = 10000001",
        "count = 1000",
        "groups[0].count",
        "1 to 10000000",
    );
    rejects(
        ANTS,
        "name = \"others\"",
        "name = \"colony\"",
        "name = \"colony\"\nmodel = \"ant\"\ncount = 10",
        "groups[1].name",
        "duplicate group name",
    );
    // Ant groups need a nest, naming a nest.
    rejects(
        ANTS,
        "count = 20\nnest = \"nest\"\n",
        "count = 20\n",
        "[[groups]]",
        "groups[0].nest",
        "missing field `nest`",
    );
    rejects(
        ANTS,
        "nest = \"nest\"",
        "nest = \"food\"",
        "nest = \"food\"",
        "groups[0].nest",
        "`food` is a `food`",
    );
    rejects(
        ANTS,
        "nest = \"nest\"",
        "nest = \"home\"",
        "\"home\"",
        "groups[0].nest",
        "no object named `home`",
    );
    // Models and worlds.
    rejects(
        ANTS,
        "model = \"ant\"",
        "model = \"bee\"",
        "\"bee\"",
        "groups[0].model",
        "3D",
    );
    // (Without its bee parameter table, which an ant group would refuse first.)
    let text = edit(BEES, "bee = { preset = \"around_nest\", kappa2 = 3.0 }", "");
    rejects(
        &text,
        "model = \"bee\"",
        "model = \"ant\"",
        "\"ant\"",
        "groups[0].model",
        "2D",
    );
    rejects(
        BEES,
        "goal = \"nest\"",
        "goal = \"pole\"",
        "\"pole\"",
        "groups[0].goal",
        "expected an object of kind `target`",
    );
    rejects(
        BEES,
        "goal = \"nest\"",
        "nest = \"nest\"",
        "nest = \"nest\"",
        "groups[0].nest",
        "for ant groups",
    );
    rejects(
        ANTS,
        "nest = \"nest\"",
        "nest = \"nest\"\nbee = { h = 2 }",
        "bee = ",
        "groups[0].bee",
        "bee parameters in an ant group",
    );
}

#[test]
fn parameter_overrides_are_validated_by_the_controllers() {
    let d = rejects(
        ANTS,
        "nest = \"nest\"",
        "nest = \"nest\"\nant = { theta = 4.0 }",
        "ant = {",
        "groups[0].ant.theta",
        "invalid ant parameter `theta`",
    );
    // What the parameter takes comes from swarm-core's parameter table.
    assert!(
        d.message.contains("a number in (0, 3.1415927] (rad)"),
        "{}",
        d.message
    );
    rejects(
        ANTS,
        "radius = 5 }",
        "radius = 5 }\n[groups.ant]\ncollect_ticks = 0",
        "collect_ticks = 0",
        "groups[0].ant.collect_ticks",
        "an integer from 1 to 65535 (ticks)",
    );
    rejects(
        BEES,
        "kappa2 = 3.0",
        "h = 0",
        "bee = {",
        "groups[0].bee.h",
        "invalid bee parameter `h`",
    );
    // Drag so strong one explicit step would reverse the velocity (dt 0.05 in the presets).
    rejects(
        BEES,
        "kappa2 = 3.0",
        "damping = 40",
        "bee = {",
        "groups[0].bee.damping",
        "damping·dt ≤ 1",
    );
    let ok = edit(BEES, "kappa2 = 3.0", "damping = 2.5");
    assert_eq!(
        bee_params(&Scenario::from_str(&ok, FILE).unwrap().groups[0])
            .unwrap()
            .damping,
        2.5
    );
    // Fixed point: a value f32 accepts but I16F16 cannot hold.
    let big = edit(BEES, "kappa2 = 3.0", "stiffness = 15000.0");
    assert!(Scenario::from_str(&big, FILE).is_ok());
    let text = edit(&big, "count = 30", "count = 30\nscalar = \"fixed\"");
    assert!(Scenario::from_str(&text, FILE).is_ok());
    // Fixed point squares the neighbour ranges: they must stay below 181.
    let wide = edit(
        ANTS,
        "nest = \"nest\"",
        "nest = \"nest\"\nant = { contact_range = 200.0 }",
    );
    assert!(Scenario::from_str(&wide, FILE).is_ok(), "f32 takes it");
    rejects(
        &wide,
        "count = 20",
        "count = 20\nscalar = \"fixed\"",
        "ant = {",
        "groups[0].ant.contact_range",
        "contact_range = 200 is too large for a fixed-point group",
    );
    let wide = edit(BEES, "kappa2 = 3.0", "kappa2 = 3.0, h = 181.0");
    assert!(Scenario::from_str(&wide, FILE).is_ok(), "f32 takes it");
    rejects(
        &wide,
        "count = 30",
        "count = 30\nscalar = \"fixed\"",
        "bee = {",
        "groups[0].bee.h",
        "the neighbour range h + 2·radius = 181.5 is too large",
    );
    rejects(
        BEES,
        "preset = \"around_nest\"",
        "preset = \"meadow\"",
        "\"meadow\"",
        "groups[0].bee.preset",
        "unknown variant `meadow`",
    );
}

#[test]
fn spawn_rules() {
    rejects(
        ANTS,
        "radius = 5 }",
        "radius = 25 }",
        "radius = 25",
        "groups[0].spawn.radius",
        "reaches outside the world",
    );
    rejects(
        ANTS,
        "radius = 5 }",
        "radius = -1 }",
        "radius = -1",
        "groups[0].spawn.radius",
        "positive",
    );
    rejects(
        ANTS,
        "max = [70, 20]",
        "max = [170, 20]",
        "max = [170",
        "groups[1].spawn.max",
        "outside the world",
    );
    rejects(
        ANTS,
        "min = [60, 10]",
        "min = [60, 10, 0]",
        "[60, 10, 0]",
        "groups[1].spawn.min",
        "expected 2 numbers",
    );
    rejects(
        ANTS,
        "spawn = { min = [60, 10]",
        "spawn = { at = \"nest\", min = [60, 10]",
        "at = \"nest\", min",
        "groups[1].spawn.min",
        "cannot be combined",
    );
    rejects(
        ANTS,
        "spawn = { at = \"nest\", radius = 5 }",
        "spawn = { at = \"nowhere\", radius = 5 }",
        "\"nowhere\"",
        "groups[0].spawn.at",
        "no object named `nowhere`",
    );
    rejects(
        ANTS,
        "radius = 5 }",
        "radius = 5, heading = [0, 0] }",
        "heading",
        "groups[0].spawn.heading",
        "non-zero",
    );
    let text = edit(ANTS, "radius = 5 }", "radius = 5, heading = [1, 0] }");
    let s = Scenario::from_str(&text, FILE).unwrap();
    assert_eq!(s.groups[0].spawn.heading, Some(vec![1.0, 0.0]));
}

#[test]
fn object_rules() {
    rejects(
        ANTS,
        "center = [80, 25]",
        "center = [180, 25]",
        "[180, 25]",
        "objects[1].center",
        "outside the world",
    );
    rejects(
        ANTS,
        "radius = 4\n",
        "radius = -4\n",
        "radius = -4",
        "objects[2].radius",
        "positive",
    );
    rejects(
        ANTS,
        "name = \"food\"",
        "name = \"nest\"",
        "name = \"nest\"\nkind = \"food\"",
        "objects[1].name",
        "duplicate object name `nest`",
    );
    rejects(
        ANTS,
        "kind = \"rock\"",
        "kind = \"sphere\"",
        "[50, 25]",
        "objects[2].center",
        "expected 3 numbers",
    );
    rejects(
        ANTS,
        "kind = \"rock\"\ncenter = [50, 25]",
        "kind = \"sphere\"\ncenter = [50, 25, 1]",
        "\"sphere\"",
        "objects[2].kind",
        "3D world",
    );
    rejects(
        ANTS,
        "kind = \"food\"\ncenter = [80, 25]\nradius = 3",
        "kind = \"food\"\ncenter = [80, 25]\nradius = 3\namount = 0",
        "amount = 0",
        "objects[1].amount",
        "endless",
    );
    let bow = "\n[[objects]]\nname = \"bow\"\nkind = \"polygon\"\npoints = [[10, 10], [20, 20], [20, 10], [10, 20]]\n";
    let text = format!("{ANTS}{bow}");
    refused_at(&text, "points = ", "objects[4].points", "not simple");
    let text = format!(
        "{ANTS}{}",
        bow.replace(
            "[[10, 10], [20, 20], [20, 10], [10, 20]]",
            "[[10, 10], [20, 20]]"
        )
    );
    refused_at(&text, "points = ", "objects[4].points", "at least 3 points");
    let text = format!("{ANTS}{}", bow.replace("[10, 20]]", "[10, 200]]"));
    refused_at(
        &text,
        "points = ",
        "objects[4].points[3]",
        "outside the world",
    );
    rejects(
        BEES,
        "y_max = 20",
        "y_max = 25",
        "y_max = 25",
        "objects[1].y_max",
        "y range",
    );
    rejects(
        BEES,
        "particles = 50",
        "particles = 0",
        "particles = 0",
        "objects[0].particles",
        "1 to",
    );
    rejects(
        BEES,
        "center = [15, 15]",
        "center = [15, 10, 15]",
        "[15, 10, 15]",
        "objects[1].center",
        "[x, z]",
    );
}

#[test]
fn event_rules() {
    rejects(
        ANTS,
        "add = \"rock\"",
        "add = \"boulder\"",
        "\"boulder\"",
        "events[0].add",
        "no object named `boulder`",
    );
    rejects(
        ANTS,
        "start = \"danger\"",
        "start = \"rock\"",
        "start = \"rock\"",
        "events[1].start",
        "applies to disturbances",
    );
    rejects(
        ANTS,
        "step = 30",
        "step = 100",
        "step = 100",
        "events[2].step",
        "`steps` = 100",
    );
    rejects(
        ANTS,
        "step = 20",
        "step = 5",
        "step = 5",
        "events[1].step",
        "step order",
    );
    rejects(
        ANTS,
        "to = [80, 30]",
        "to = [80, 30, 1]",
        "to = [80, 30, 1]",
        "events[2].move.to",
        "expected 2 numbers",
    );
    rejects(
        ANTS,
        "to = [80, 30]",
        "to = [80, 300]",
        "to = [80, 300]",
        "events[2].move.to",
        "outside the world",
    );
    let text = edit(ANTS, "object = \"food\"", "object = \"danger\"");
    assert!(
        Scenario::from_str(&text, FILE).is_ok(),
        "a disturbance can move"
    );
    rejects(
        ANTS,
        "active = false\n\n[[objects]]\nname = \"danger\"",
        "\n[[objects]]\nname = \"danger\"",
        "add = \"rock\"",
        "events[0].add",
        "already present",
    );
    rejects(
        ANTS,
        "add = \"rock\"",
        "remove = \"rock\"",
        "remove = \"rock\"",
        "events[0].remove",
        "not present",
    );
    rejects(
        ANTS,
        "start = \"danger\"",
        "stop = \"danger\"",
        "stop = \"danger\"",
        "events[1].stop",
        "not acting",
    );
    rejects(
        ANTS,
        "add = \"rock\"",
        "add = \"rock\"\nremove = \"food\"",
        "remove = \"food\"",
        "events[0].remove",
        "exactly one action",
    );
    rejects(
        ANTS,
        "add = \"rock\"",
        "",
        "[[events]]",
        "events[0]",
        "needs one action",
    );
    // Bees: a shaft moves in [x, z].
    let moved =
        format!("{BEES}\n[[events]]\nstep = 10\nmove = {{ object = \"pole\", to = [5, 5] }}\n");
    assert!(Scenario::from_str(&moved, FILE).is_ok());
    let text = moved.replace("to = [5, 5]", "to = [5, 5, 5]");
    refused_at(
        &text,
        "to = [5, 5, 5]",
        "events[0].move.to",
        "expected 2 numbers",
    );
}

#[test]
fn display_shows_the_source_line_and_a_caret() {
    let text = edit(ANTS, "count = 20", "count = 0");
    let shown = Scenario::from_str(&text, FILE).unwrap_err().to_string();
    let line = line_of(&text, "count = 0");
    assert!(
        shown.starts_with(&format!(
            "{FILE}:{line}:9: invalid scenario in `groups[0].count`: "
        )),
        "{shown}"
    );
    assert!(
        shown.contains(&format!("\n {line} | count = 0\n")),
        "{shown}"
    );
    assert!(shown.ends_with("|         ^"), "{shown:?}");
}

#[test]
fn read_and_resolve_errors() {
    let err = Scenario::from_path(Path::new("/no/such/dir/x.toml")).unwrap_err();
    assert!(matches!(err, SimError::ScenarioRead { .. }));
    assert!(err.to_string().contains("/no/such/dir/x.toml"));
    let err = resolve("no-such-scenario").unwrap_err();
    assert!(matches!(err, SimError::ScenarioNotFound { .. }));
    assert!(err.to_string().contains("ants-fig7a-single-colony"));
    // A file: errors name it.
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("mine.toml");
    std::fs::write(&path, edit(ANTS, "count = 20", "count = 0")).unwrap();
    let err = resolve(path.to_str().unwrap()).unwrap_err();
    let d = err.diagnostic().unwrap();
    assert_eq!(d.file, path.display().to_string());
    std::fs::write(&path, ANTS.replace("name = \"test\"\n", "")).unwrap();
    let s = resolve(path.to_str().unwrap()).unwrap();
    assert_eq!(s.name, "mine");
    assert_eq!(s.source.as_deref(), Some(path.as_path()));
}

#[test]
fn object_ids_and_lookups() {
    let s = Scenario::from_str(ANTS, FILE).unwrap();
    assert_eq!(s.object_id("nest"), Some(0));
    assert_eq!(s.object_id("danger"), Some(3));
    assert_eq!(s.object_id("nothing"), None);
    assert_eq!(s.object("food").unwrap().kind.tag(), "food");
    assert_eq!(s.group("others").unwrap().count, 10);
    assert_eq!(s.agent_count(), 30);
    assert!(s.object("rock").unwrap().kind.is_obstacle());
    assert!(!s.object("rock").unwrap().active);
}

#[test]
fn set_steps_drops_late_events() {
    let mut s = Scenario::from_str(ANTS, FILE).unwrap();
    s.set_steps(25);
    assert_eq!(s.steps, 25);
    assert_eq!(s.events.len(), 2);
    assert!(s.validate().is_ok());
    s.steps = 15;
    let err = s.validate().unwrap_err();
    let d = err.diagnostic().unwrap();
    assert_eq!((d.field.as_str(), d.line), ("events[1].step", None));
}

#[test]
fn overrides_apply_on_their_base() {
    let mut o = AntParamsOverride::default();
    assert!(o.set("speed", ParamValue::Real(2.0)));
    assert!(o.set("k", ParamValue::Int(3)));
    let p = o.apply(AntParams::default());
    assert_eq!((p.speed, p.k), (2.0, 3));
    assert_eq!(p.theta, AntParams::<f32>::default().theta);
    assert_eq!(AntParamsOverride::names().count(), 13);
    let mut b = BeeParamsOverride {
        preset: Some(BeePreset::Grassland),
        ..Default::default()
    };
    assert!(b.overrides.set("h", ParamValue::Real(2.5)));
    let p = b.params();
    assert_eq!(p.h, 2.5);
    assert_eq!(p.kappa2, BeeParams::<f32>::grassland().kappa2);
    assert_eq!(BeeParamsOverride::default().params(), BeeParams::default());
    assert_eq!(ParamsOverride::<BeeParams<f32>>::names().count(), 17);
}

#[test]
fn target_particles_cover_the_sphere() {
    let s = builtin("bees-fig15-nest").unwrap();
    let nest = s.object("nest").unwrap();
    let ObjectKind::Target {
        center,
        radius,
        particles,
    } = nest.kind
    else {
        panic!("the nest is a target");
    };
    let pts = nest.sample_particles();
    assert_eq!(pts.len(), particles as usize);
    assert_eq!(pts, nest.sample_particles(), "deterministic");
    let mut mean = [0.0f64; 3];
    for p in &pts {
        let d: f32 = (0..3)
            .map(|i| (p[i] - center[i]).powi(2))
            .sum::<f32>()
            .sqrt();
        assert!((d - radius).abs() < 1e-4, "on the surface: {d}");
        for i in 0..3 {
            mean[i] += f64::from(p[i] - center[i]) / pts.len() as f64;
        }
    }
    assert!(
        mean.iter().all(|m| m.abs() < 0.05 * f64::from(radius)),
        "evenly spread: {mean:?}"
    );
    assert!(s.object("ground").unwrap().sample_particles().is_empty());
}

#[test]
fn worlds_and_kinds() {
    let w = World::Space {
        min: [0.0; 3],
        max: [10.0; 3],
    };
    assert_eq!(w.dim(), 3);
    assert!(w.contains(&[5.0, 10.0, 0.0]));
    assert!(!w.contains(&[5.0, 10.1, 0.0]));
    assert!(!w.contains(&[5.0, 5.0]));
    let mut k = ObjectKind::Shaft {
        center: [1.0, 2.0],
        radius: 1.0,
        y_min: 0.0,
        y_max: 5.0,
    };
    assert_eq!(k.point(), None);
    assert!(k.set_center(&[3.0, 4.0]));
    assert!(!k.set_center(&[3.0, 4.0, 5.0]));
    assert_eq!(k.center(), Some(&[3.0, 4.0][..]));
    assert_eq!(ScalarType::Fixed.kind(), swarm_core::ScalarKind::I16F16);
}

/// Whether `p` lies inside the obstacle `kind` (2D or 3D).
fn inside_obstacle(kind: &ObjectKind, p: &[f32]) -> bool {
    let dist = |a: &[f32], b: &[f32]| {
        a.iter()
            .zip(b)
            .map(|(x, y)| (x - y).powi(2))
            .sum::<f32>()
            .sqrt()
    };
    match kind {
        ObjectKind::Rock { center, radius } => dist(p, center) <= *radius,
        ObjectKind::Sphere { center, radius } => dist(p, center) <= *radius,
        ObjectKind::Shaft {
            center,
            radius,
            y_min,
            y_max,
        } => dist(&[p[0], p[2]], center) <= *radius && p[1] >= *y_min && p[1] <= *y_max,
        ObjectKind::Box { min, max } => (0..3).all(|i| p[i] >= min[i] && p[i] <= max[i]),
        ObjectKind::Polygon { points } => {
            // Even-odd ray casting.
            let mut inside = false;
            for i in 0..points.len() {
                let (a, b) = (points[i], points[(i + 1) % points.len()]);
                if (a[1] > p[1]) != (b[1] > p[1])
                    && p[0] < a[0] + (p[1] - a[1]) / (b[1] - a[1]) * (b[0] - a[0])
                {
                    inside = !inside;
                }
            }
            inside
        }
        _ => false,
    }
}

#[test]
fn builtin_spawn_regions_and_destinations_are_clear_of_obstacles() {
    for b in BUILTINS {
        let s = builtin(b.name).unwrap();
        let obstacles: Vec<&Object> = s
            .objects
            .iter()
            .filter(|o| o.active && o.kind.is_obstacle())
            .collect();
        // Checks that the point `p` of `what` is inside no obstacle.
        let outside = |p: &[f32], what: &str| {
            for o in &obstacles {
                let name = &o.name;
                assert!(
                    !inside_obstacle(&o.kind, p),
                    "{}: {what} inside `{name}`",
                    b.name
                );
            }
        };
        for g in &s.groups {
            // A grid of points over the spawn region.
            let (lo, hi): (Vec<f32>, Vec<f32>) = match &g.spawn.region {
                SpawnRegion::Around { at, radius } => {
                    let c = s.object(at).unwrap().kind.point().unwrap();
                    (
                        c.iter().map(|v| v - radius).collect(),
                        c.iter().map(|v| v + radius).collect(),
                    )
                }
                SpawnRegion::Box { min, max } => (min.clone(), max.clone()),
            };
            let n = 12;
            let axis = |i: usize, k: usize| lo[i] + (hi[i] - lo[i]) * k as f32 / n as f32;
            let mut points = Vec::new();
            for a in 0..=n {
                for b2 in 0..=n {
                    if lo.len() == 2 {
                        points.push(vec![axis(0, a), axis(1, b2)]);
                    } else {
                        for c in 0..=n {
                            points.push(vec![axis(0, a), axis(1, b2), axis(2, c)]);
                        }
                    }
                }
            }
            for p in &points {
                outside(p, &format!("group `{}` may spawn at {p:?}", g.name));
            }
        }
        // Nests, food sources, way points and targets are reachable: their centres are not
        // inside an obstacle.
        for o in &s.objects {
            if let (false, Some(c)) = (o.kind.is_obstacle(), o.kind.point()) {
                outside(c, &format!("`{}` lies", o.name));
            }
        }
    }
}
