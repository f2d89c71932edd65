//! Tests of the sanity checks of a layout (`sanity/`): what is refused, what is a warning,
//! where each is reported.

use super::{edit, expect_error, line_of};
use crate::SimError;
use crate::scenario::{
    BUILTINS, DiagnosticKind, Scenario, ScenarioWarning, WarningKind, resolve_with_warnings,
};

/// An ant world: a nest, a food source, a rock and a concave polygon (a U open upwards,
/// its notch x 110..120, y 10..30) well apart; the tests move things into each other.
const ANTS: &str = include_str!("ant_world.toml");

const BEES: &str = include_str!("bee_world.toml");
fn warnings(text: &str) -> Vec<ScenarioWarning> {
    Scenario::from_str_with_warnings(text, "t.toml")
        .unwrap_or_else(|e| panic!("{e}"))
        .1
}

/// The one warning `text` loads with.
#[track_caller]
fn one_warning(text: &str) -> ScenarioWarning {
    let mut w = warnings(text);
    assert_eq!(w.len(), 1, "{w:?}");
    w.remove(0)
}

/// Loads `text`, expects it refused by a rule at the line of `at` / `field`, with a message
/// naming `names`; the serde path refuses it too.
#[track_caller]
fn refused(text: &str, at: &str, field: &str, names: &[&str]) {
    let d = expect_error(text, line_of(text, at), field, "");
    assert_eq!(d.kind, DiagnosticKind::Rule, "{d}");
    for n in names {
        assert!(
            d.message.contains(&format!("`{n}`")),
            "should name `{n}`: {d}"
        );
    }
    assert!(toml::from_str::<Scenario>(text).is_err());
}

#[test]
fn the_base_scenarios_load_without_warnings() {
    assert!(warnings(ANTS).is_empty());
    assert!(warnings(BEES).is_empty());
}

#[test]
fn every_builtin_loads_without_warnings() {
    for b in BUILTINS {
        let (_, w) = resolve_with_warnings(b.name).unwrap_or_else(|e| panic!("{e}"));
        assert!(w.is_empty(), "{}: {:?}", b.name, w);
    }
}

#[test]
fn food_inside_an_obstacle_is_refused_naming_both() {
    // Inside the rock.
    let t = edit(ANTS, "center = [180, 50]", "center = [62, 52]");
    refused(
        &t,
        "center = [62, 52]",
        "objects[1].center",
        &["food", "boulder"],
    );
    // Inside a leg of the concave polygon.
    let t = edit(ANTS, "center = [180, 50]", "center = [105, 15]");
    refused(
        &t,
        "center = [105, 15]",
        "objects[1].center",
        &["food", "u"],
    );
    // In the notch of the U: outside the polygon, fine.
    let t = edit(ANTS, "center = [180, 50]", "center = [115, 20]");
    assert!(warnings(&t).is_empty());
    // Across the rock's rim: a warning, not an error.
    let t = edit(ANTS, "center = [180, 50]", "center = [70, 50]");
    let w = one_warning(&t);
    assert_eq!(w.kind, WarningKind::FoodOverlapsObstacle);
    assert_eq!(w.diagnostic.field, "objects[1].center");
    assert_eq!(w.diagnostic.line, Some(line_of(&t, "center = [70, 50]")));
    assert!(
        w.to_string().contains("warning in `objects[1].center`"),
        "{}",
        w
    );
}

#[test]
fn a_way_point_inside_an_obstacle_is_refused() {
    let t = format!(
        "{ANTS}\n[[objects]]\nname = \"wp\"\nkind = \"waypoint\"\ncenter = [60, 48]\nradius = 2\norder = 1\n"
    );
    refused(
        &t,
        "center = [60, 48]",
        "objects[4].center",
        &["wp", "boulder"],
    );
}

#[test]
fn a_nest_in_or_on_an_obstacle_is_a_warning() {
    let t = edit(ANTS, "center = [20, 50]", "center = [60, 50]");
    let w = warnings(&t);
    assert!(
        w.iter().any(|w| w.kind == WarningKind::NestInObstacle
            && w.diagnostic.message.contains("entirely inside")
            && w.diagnostic.message.contains("`boulder`")),
        "{w:?}"
    );
    // Its ants spawn inside the rock too.
    assert!(
        w.iter().any(|w| w.kind == WarningKind::SpawnInObstacle
            && w.diagnostic.field == "groups[0].spawn"
            && w.diagnostic.message.contains("the whole spawn region")),
        "{w:?}"
    );
    let t = edit(ANTS, "center = [20, 50]", "center = [48, 50]");
    let w = warnings(&t);
    assert!(
        w.iter()
            .any(|w| w.kind == WarningKind::NestInObstacle
                && w.diagnostic.message.contains("overlaps")),
        "{w:?}"
    );
}

#[test]
fn a_spawn_region_partly_inside_obstacles_is_a_warning() {
    let t = edit(
        ANTS,
        "spawn = { at = \"nest\", radius = 4 }",
        "spawn = { min = [40, 40], max = [60, 60] }",
    );
    let w = one_warning(&t);
    let d = &w.diagnostic;
    assert_eq!(
        (w.kind, d.field.as_str()),
        (WarningKind::SpawnInObstacle, "groups[0].spawn")
    );
    // Half the rock's disc in a 20 x 20 box: π·100/2 / 400 ≈ 39 %.
    assert!(
        d.message.contains("about 39 %") && d.message.contains("`boulder`"),
        "{}",
        w
    );
    assert_eq!(d.line, Some(line_of(&t, "spawn = { min")));
}

#[test]
fn a_nest_covering_food_is_a_warning() {
    let t = edit(ANTS, "center = [180, 50]", "center = [22, 50]");
    let w = one_warning(&t);
    assert_eq!(w.kind, WarningKind::NestCoversFood);
    assert!(w.diagnostic.message.contains("`nest`"), "{}", w);
}

#[test]
fn events_are_checked() {
    // Moving the food into the rock is refused at the event.
    let t =
        format!("{ANTS}\n[[events]]\nstep = 50\nmove = {{ object = \"food\", to = [60, 50] }}\n");
    refused(
        &t,
        "to = [60, 50]",
        "events[0].move.to",
        &["food", "boulder"],
    );
    // Moving the nest onto the food is a warning.
    let t =
        format!("{ANTS}\n[[events]]\nstep = 50\nmove = {{ object = \"nest\", to = [180, 52] }}\n");
    let w = warnings(&t);
    assert!(
        w.iter().any(|w| w.kind == WarningKind::NestCoversFood
            && w.diagnostic.field == "events[0].move.to"
            && w.diagnostic.message.contains("step 50")),
        "{w:?}"
    );
    // A rock dropped over the food later is a warning (a blocked source is an experiment);
    // an inactive rock over the food at the start is not checked until it appears.
    let t = format!(
        "{ANTS}\n[[objects]]\nname = \"lid\"\nkind = \"rock\"\ncenter = [180, 50]\nradius = 5\nactive = false\n\n[[events]]\nstep = 40\nadd = \"lid\"\n\n[[events]]\nstep = 60\nremove = \"lid\"\n"
    );
    let w = one_warning(&t);
    assert_eq!(w.kind, WarningKind::EventCoversFood);
    assert_eq!(w.diagnostic.field, "events[0].add");
    assert_eq!(w.diagnostic.line, Some(line_of(&t, "add = \"lid\"")));
    // Food added into a rock that is present is refused.
    let t = format!(
        "{ANTS}\n[[objects]]\nname = \"late\"\nkind = \"food\"\ncenter = [58, 50]\nradius = 2\nactive = false\n\n[[events]]\nstep = 40\nadd = \"late\"\n"
    );
    refused(&t, "add = \"late\"", "events[0].add", &["late", "boulder"]);
    // Once `--steps` drops an event, its warnings no longer apply.
    let mut sc = Scenario::from_str(&format!(
        "{ANTS}\n[[objects]]\nname = \"lid\"\nkind = \"rock\"\ncenter = [180, 50]\nradius = 5\nactive = false\n\n[[events]]\nstep = 40\nadd = \"lid\"\n"
    ), "t.toml").unwrap();
    let w = sc.warnings();
    assert_eq!(w.len(), 1);
    assert_eq!(
        (w[0].diagnostic.line, w[0].diagnostic.file.as_str()),
        (None, "t")
    );
    assert!(w[0].applies_to(&sc));
    sc.set_steps(30);
    assert!(!w[0].applies_to(&sc));
    assert!(sc.warnings().is_empty());
}

#[test]
fn bee_targets_inside_obstacles_are_refused() {
    let t = edit(BEES, "center = [40, 15, 40]", "center = [30, 15, 30]");
    refused(
        &t,
        "center = [30, 15, 30]",
        "objects[0].center",
        &["flower", "pole"],
    );
    let t = edit(BEES, "center = [40, 15, 40]", "center = [40, 0.5, 40]\n#");
    // Half sunk in the ground: reachable from above, no error.
    assert!(Scenario::from_str(&t, "t.toml").is_ok());
    let t = edit(BEES, "radius = 2\n", "radius = 0.4\n");
    let t = edit(&t, "center = [40, 15, 40]", "center = [40, 0.5, 40]");
    refused(
        &t,
        "center = [40, 0.5, 40]",
        "objects[0].center",
        &["flower", "ground"],
    );
    let t = format!(
        "{BEES}\n[[events]]\nstep = 10\nmove = {{ object = \"flower\", to = [30, 20, 30] }}\n"
    );
    refused(
        &t,
        "to = [30, 20, 30]",
        "events[0].move.to",
        &["flower", "pole"],
    );
    // A spawn box in the ground.
    let t = edit(
        BEES,
        "spawn = { min = [2, 5, 2], max = [10, 15, 10] }",
        "spawn = { min = [2, 0, 2], max = [10, 2, 10] }",
    );
    let w = one_warning(&t);
    assert_eq!(w.kind, WarningKind::SpawnInObstacle);
    assert!(w.diagnostic.message.contains("about 50 %"), "{}", w);
}

#[test]
fn validate_refuses_what_code_changed() {
    let mut sc = Scenario::from_str(ANTS, "t.toml").unwrap();
    sc.objects[1].kind.set_center(&[60.0, 50.0]);
    let err = sc.validate().unwrap_err();
    assert!(
        matches!(&err, SimError::InvalidScenario(d) if d.field == "objects[1].center"),
        "{err}"
    );
}
