//! The built-in scenarios: the files of `scenarios/` compiled into the binary, one per paper
//! figure, each runnable by name (`swarm run ants-fig7a-single-colony`).

use std::path::Path;

use super::load::load;
use super::types::Scenario;
use super::warning::ScenarioWarning;
use crate::{Result, SimError};

/// A built-in scenario file.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Builtin {
    /// Its name: the file stem in `scenarios/`.
    pub name: &'static str,
    /// One line saying what it shows (for `swarm list`).
    pub summary: &'static str,
    /// The TOML text.
    pub text: &'static str,
}

macro_rules! builtins {
    ($($name:literal => $summary:literal,)*) => {
        /// Every built-in scenario, in `swarm list` order.
        pub const BUILTINS: &[Builtin] = &[$(Builtin {
            name: $name,
            summary: $summary,
            text: include_str!(concat!("../../../scenarios/", $name, ".toml")),
        }),*];

        const NAMES: &[&str] = &[$($name),*];
    };
}

builtins! {
    "ants-fig7a-single-colony" => "xiang2018 Fig. 7a: 500 ants, one nest, one food source",
    "ants-fig7b-obstacles" => "xiang2018 Fig. 7b: one colony, rocks between nest and food",
    "ants-fig8a-hybrid" => "xiang2018 Fig. 8a: three colonies and three food sources",
    "ants-fig8b-hybrid-obstacles" => "xiang2018 Fig. 8b: three colonies, food sources and obstacles",
    "ants-fig11-dynamic-obstacles" => "xiang2018 Fig. 11: three rocks dropped on the trail, then removed",
    "ants-fig12-moved-food" => "xiang2018 Fig. 12: the food source moved mid-run",
    "ants-fig13-disturbance" => "xiang2018 Fig. 13: a disturbance on the trail, later lifted",
    "ants-fig1c-heart" => "xiang2018 Fig. 1c: obstacles shape the colony into a heart",
    "ants-fig14-waypoints" => "xiang2018 Fig. 14: way points lead the colony along a zig-zag",
    "bees-fig11-grassland" => "chen Fig. 11: 1000 bees swarming over grassland",
    "bees-fig15-nest" => "chen Fig. 15: 350 bees around a nest, zig-zag approach",
    "bees-fig14-shafts" => "chen Fig. 14: a swarm flying through vertical shafts to a goal",
    "wang-fig6-two-blocks" => "wang2014 Fig. 6: 300 insects through the passage between two blocks",
    "wang-fig7-min-cost" => "wang2014 Fig. 7: minimum-cost paths through, round and over two blocks",
    "wang-fig8-chasing" => "wang2014 Fig. 8: 100 insects chase a ball moved every 25 s",
    "wang-fig9-aggregation" => "wang2014 Fig. 9: 1000 insects swarm where they started",
    "wang-fig10-phototaxis" => "wang2014 Fig. 10: 30 moths drawn to a street lamp",
    "wang-fig1a-locusts" => "wang2014 Fig. 1a: 5000 locusts cross a hamlet",
    "wang-fig13-noise-compare" => "wang2014 Fig. 11/13: curl vs Perlin vs random noise",
    "fly-fig1-midges" => "ren2016 Fig. 1: 100 midges swarming in a glass box",
    "fly-fig2-fruitfly" => "ren2016 Fig. 2: 100 fruit flies swarming in a glass box",
    "fly-fig3-aggregation" => "ren2016 Fig. 3: 500 midges aggregating at 9,470 /m³",
    "fly-fig3-aggregation-3000" => "ren2016 Fig. 3: 3000 midges aggregating at 56,818 /m³",
    "fly-fig4-locusts" => "ren2016 Fig. 4: 2000 locusts pass a hamlet to a crop field",
    "fly-fig5-mating" => "ren2016 Fig. 5: 100 males pursue a female flying through the swarm",
    "fly-fig6-phase" => "ren2016 Fig. 6: 200 insects in the ordered phase fly off together",
    "fly-fig7-phototaxis" => "ren2016 Fig. 7: 80 moths gather at a street lamp",
    "fly-fig8-escape" => "ren2016 Fig. 8: 100 flies escape a predator crossing the swarm",
    "fly-fig9-bats" => "ren2016 Fig. 9: 500 bats echolocating in a cave mill round its axis",
    "li-fig4-confined" => "li2015 Fig. 4: 100 insects sample waypoints toward a measured density",
    "li-fig5-lantern" => "li2015 Fig. 5 left: 200 midges swarm on a sketched ring round a lantern",
    "li-fig5-butterflies" => "li2015 Fig. 5 right: 50 butterflies follow a sketched S over a prairie",
    "li-fig6-lights" => "li2015 Fig. 6: 100 moths travel to three lights in turn, round obstacles",
    "li-fig8-9-cells" => "li2015 Figs. 8-9: the Fig. 4 swarm with 2³ density cells spreads out",
}

/// The names of the built-in scenarios (their summaries: [`BUILTINS`]).
pub fn builtin_names() -> &'static [&'static str] {
    NAMES
}

/// The built-in scenario `name`, loaded and checked; `None` if there is no such built-in.
pub fn builtin(name: &str) -> Option<Scenario> {
    load_builtin(name).and_then(|r| r.ok()).map(|(s, _)| s)
}

/// The built-in `name` with its load result (a built-in that fails to load is a bug that the
/// tests catch; this keeps the message instead of hiding it).
fn load_builtin(name: &str) -> Option<Result<(Scenario, Vec<ScenarioWarning>)>> {
    BUILTINS
        .iter()
        .find(|b| b.name == name)
        .map(|b| load(b.text, &format!("scenarios/{}.toml", b.name), b.name, None))
}

/// A built-in scenario by name, else the scenario file at that path.
pub fn resolve(name_or_path: &str) -> Result<Scenario> {
    resolve_with_warnings(name_or_path).map(|(s, _)| s)
}

/// [`resolve`], with the scenario's warnings (file, line, field and message of each).
pub fn resolve_with_warnings(name_or_path: &str) -> Result<(Scenario, Vec<ScenarioWarning>)> {
    if let Some(result) = load_builtin(name_or_path) {
        return result;
    }
    let path = Path::new(name_or_path);
    if path.exists() {
        return Scenario::from_path_with_warnings(path);
    }
    Err(SimError::ScenarioNotFound {
        name: name_or_path.to_owned(),
        builtins: NAMES,
    })
}
