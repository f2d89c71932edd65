//! Loading: TOML text → checked [`Scenario`], with errors that name the file, line, column and
//! field.
//!
//! Three stages, each reporting the first problem it finds:
//! 1. TOML syntax (the parser's own position);
//! 2. shape: serde into the flat `raw` structs (unknown fields, wrong types, missing fields; the
//!    deserializer's span is mapped back to a field path through the parsed document) and their
//!    conversion into the typed model (fields that do not fit an object's `kind`, ...);
//! 3. rules: [`validate`] on the typed scenario, whose field path is mapped to a line through
//!    the parsed document (the nearest enclosing table when the field itself is missing).

use std::collections::HashMap;
use std::ops::Range;
use std::path::Path;

use serde::Deserialize;
use swarm_core::Fx;
use swarm_core::model::ModelParams;
use toml::Spanned;
use toml::de::{DeTable, DeValue};

use super::error::{Diagnostic, DiagnosticKind, Result, ScenarioError};
use super::raw::{Problem, RawScenario};
use super::sanity::{self, Finding};
use super::types::{
    Action, Group, MAX_AGENTS, MAX_COORD, MAX_TARGET_PARTICLES, Model, Object, ObjectKind,
    ScalarType, Scenario, SpawnRegion, World,
};
use super::warning::ScenarioWarning;

impl Scenario {
    /// Reads and checks the scenario file at `path`. The scenario's `name` defaults to the
    /// file stem, and `source` is set to `path`. Its warnings: [`Scenario::warnings`], or
    /// [`Scenario::from_path_with_warnings`] for their lines.
    pub fn from_path(path: &Path) -> Result<Scenario> {
        Self::from_path_with_warnings(path).map(|(s, _)| s)
    }

    /// [`Scenario::from_path`], with the scenario's warnings (file, line, field, message).
    pub fn from_path_with_warnings(path: &Path) -> Result<(Scenario, Vec<ScenarioWarning>)> {
        let text = std::fs::read_to_string(path).map_err(|source| ScenarioError::Read {
            path: path.to_owned(),
            source,
        })?;
        let (mut scenario, warnings) = load(&text, &path.display().to_string(), &stem(path))?;
        scenario.source = Some(path.to_owned());
        Ok((scenario, warnings))
    }

    /// Parses and checks scenario text. `origin` names the text in error messages (a file name
    /// such as `scenarios/x.toml`); the scenario's `name` defaults to its stem.
    pub fn from_str(text: &str, origin: &str) -> Result<Scenario> {
        Self::from_str_with_warnings(text, origin).map(|(s, _)| s)
    }

    /// [`Scenario::from_str`], with the scenario's warnings (file, line, field, message).
    pub fn from_str_with_warnings(
        text: &str,
        origin: &str,
    ) -> Result<(Scenario, Vec<ScenarioWarning>)> {
        load(text, origin, &stem(Path::new(origin)))
    }

    /// Checks a scenario built or changed in code by the same rules as a loaded file (the
    /// diagnostic has no line: there is no file).
    pub fn validate(&self) -> Result<()> {
        validate(self)
            .map(drop)
            .map_err(|p| ScenarioError::Invalid(Box::new(self.unlocated(DiagnosticKind::Rule, p))))
    }

    /// The warnings of a valid scenario (none if it is invalid), without lines: they name the
    /// file (or the scenario) and the field. A loaded file's warnings with their lines come
    /// from [`Scenario::from_path_with_warnings`] and [`resolve_with_warnings`].
    ///
    /// [`resolve_with_warnings`]: super::resolve_with_warnings
    pub fn warnings(&self) -> Vec<ScenarioWarning> {
        validate(self)
            .unwrap_or_default()
            .into_iter()
            .map(|f| ScenarioWarning {
                kind: f.kind,
                diagnostic: self.unlocated(DiagnosticKind::Warning, f.problem),
            })
            .collect()
    }

    /// A diagnostic without a line, naming the file (or the scenario).
    fn unlocated(&self, kind: DiagnosticKind, p: Problem) -> Diagnostic {
        let file = self
            .source
            .as_ref()
            .map_or_else(|| self.name.clone(), |s| s.display().to_string());
        Diagnostic {
            kind,
            file,
            line: None,
            column: None,
            field: p.path,
            message: p.message,
            source_line: None,
        }
    }
}

/// Refuses a step count given on the command line (`--steps`) by the rule of a file's
/// `steps`, with the same message; `field` names the option.
pub fn check_steps(steps: u32, field: &str) -> Result<()> {
    steps_rule(steps, field).map_err(|p| {
        ScenarioError::Invalid(Box::new(Diagnostic {
            kind: DiagnosticKind::Rule,
            file: "command line".to_owned(),
            line: None,
            column: None,
            field: p.path,
            message: p.message,
            source_line: None,
        }))
    })
}

/// A run has at least one step.
fn steps_rule(steps: u32, field: &str) -> std::result::Result<(), Problem> {
    if steps == 0 {
        return Err(Problem::new(field, "expected at least 1 step, found 0"));
    }
    Ok(())
}

fn stem(path: &Path) -> String {
    path.file_stem().map_or_else(
        || "scenario".to_owned(),
        |s| s.to_string_lossy().into_owned(),
    )
}

/// Parses, converts and validates `text`; errors and warnings name `origin`.
pub(crate) fn load(
    text: &str,
    origin: &str,
    default_name: &str,
) -> Result<(Scenario, Vec<ScenarioWarning>)> {
    let at = |kind, span: Option<Range<usize>>, field: String, message: String| {
        ScenarioError::Invalid(Box::new(diagnostic(
            text, origin, kind, span, field, message,
        )))
    };
    let tree = match DeTable::parse(text) {
        Ok(tree) => tree,
        Err(e) => {
            let (partial, _) = DeTable::parse_recoverable(text);
            let field = e
                .span()
                .map(|s| path_at(&partial, s.start))
                .unwrap_or_default();
            return Err(at(
                DiagnosticKind::Syntax,
                e.span(),
                field,
                e.message().to_owned(),
            ));
        }
    };
    let raw =
        RawScenario::deserialize(toml::de::Deserializer::from(tree.clone())).map_err(|e| {
            // A missing field is reported at its table (the whole document: an empty span at 0).
            let table = match e.span() {
                Some(s) if s.is_empty() && s.start == 0 => String::new(),
                Some(s) => path_at(&tree, s.start),
                None => String::new(),
            };
            let field = match missing_field(e.message()) {
                Some(name) => super::raw::join(&table, name),
                None => table,
            };
            let mut message = e.message().to_owned();
            if let Some(hint) = missing_field(&message).and_then(hint) {
                message = format!("{message}: expected {hint}");
            }
            at(DiagnosticKind::Shape, e.span(), field, message)
        })?;
    let rule = |kind, p: Problem| at(kind, span_of(&tree, &p.path), p.path, p.message);
    let scenario = raw
        .convert(default_name)
        .map_err(|p| rule(DiagnosticKind::Shape, p))?;
    let findings = validate(&scenario).map_err(|p| rule(DiagnosticKind::Rule, p))?;
    let warnings = findings
        .into_iter()
        .map(|f| ScenarioWarning {
            kind: f.kind,
            diagnostic: diagnostic(
                text,
                origin,
                DiagnosticKind::Warning,
                span_of(&tree, &f.problem.path),
                f.problem.path,
                f.problem.message,
            ),
        })
        .collect();
    Ok((scenario, warnings))
}

/// `x` of serde's "missing field `x`".
fn missing_field(message: &str) -> Option<&str> {
    message
        .strip_prefix("missing field `")
        .and_then(|rest| rest.split('`').next())
}

/// What a required field holds, for "missing field" messages.
fn hint(field: &str) -> Option<&'static str> {
    Some(match field {
        "steps" => "the number of steps to run, e.g. `steps = 3000`",
        "world" => {
            "the world bounds, e.g. `world = { dim = 2, min = [0, 0], max = [200, 120] }` (ants) \
             or `{ dim = 3, min = [0, 0, 0], max = [60, 30, 60] }` (bees)"
        }
        "dim" => "2 (ants) or 3 (bees)",
        "min" | "max" => "the corner coordinates, e.g. `[0, 0]`",
        "name" => "a unique name, e.g. `name = \"colony\"`",
        "model" => "`model = \"ant\"` or `model = \"bee\"`",
        "count" => "the number of agents, e.g. `count = 500`",
        "spawn" => {
            "the spawn region: `spawn = { at = \"nest\", radius = 10 }` or `spawn = { min = [..], \
             max = [..] }`"
        }
        "kind" => {
            "the object's kind: nest, food, rock, polygon, disturbance, waypoint (ants) or \
             sphere, box, shaft, target (bees)"
        }
        "step" => "the step at which the event happens, e.g. `step = 1500`",
        "object" => "the name of the object to move",
        "to" => "the new centre, e.g. `to = [120, 100]`",
        _ => return None,
    })
}

/// A diagnostic at `span` of `text` (line and column of its start).
fn diagnostic(
    text: &str,
    origin: &str,
    kind: DiagnosticKind,
    span: Option<Range<usize>>,
    field: String,
    message: String,
) -> Diagnostic {
    let (line, column, source_line) = match span {
        Some(span) => {
            let start = span.start.min(text.len());
            let before = text.get(..start).unwrap_or_default();
            let line_start = before.rfind('\n').map_or(0, |i| i + 1);
            let line = before.matches('\n').count() + 1;
            let column = text
                .get(line_start..start)
                .map_or(1, |s| s.chars().count() + 1);
            let source_line = text[line_start..]
                .lines()
                .next()
                .unwrap_or_default()
                .to_owned();
            (Some(line), Some(column), Some(source_line))
        }
        None => (None, None, None),
    };
    Diagnostic {
        kind,
        file: origin.to_owned(),
        line,
        column,
        field,
        message,
        source_line,
    }
}

/// One step of a field path.
#[derive(Debug, PartialEq)]
enum Seg<'a> {
    Key(&'a str),
    Index(usize),
}

/// `groups[1].spawn.radius` → Key(groups), Index(1), Key(spawn), Key(radius).
fn segments(path: &str) -> Vec<Seg<'_>> {
    let mut out = Vec::new();
    for part in path.split('.').filter(|p| !p.is_empty()) {
        let (key, mut rest) = part.split_at(part.find('[').unwrap_or(part.len()));
        if !key.is_empty() {
            out.push(Seg::Key(key));
        }
        while let Some(close) = rest.find(']') {
            if let Some(Ok(i)) = rest.get(1..close).map(str::parse) {
                out.push(Seg::Index(i));
            }
            rest = &rest[close + 1..];
        }
    }
    out
}

/// The span of the field at `path`, or of the deepest part of it that the document has (a
/// missing field is reported at its table, a missing top-level field at the start of the
/// document). Keys point at their value.
fn span_of(root: &Spanned<DeTable<'_>>, path: &str) -> Option<Range<usize>> {
    let mut best = Some(0..0);
    let mut table = Some(root.get_ref());
    let mut array = None;
    for seg in segments(path) {
        let found: Option<&Spanned<DeValue<'_>>> = match seg {
            Seg::Key(k) => table.and_then(|t| t.get(k)),
            Seg::Index(i) => array.and_then(|a: &toml::de::DeArray<'_>| a.get(i)),
        };
        let Some(value) = found else { break };
        best = Some(value.span());
        table = value.get_ref().as_table();
        array = value.get_ref().as_array();
    }
    best
}

/// The path of the deepest field whose key or value contains byte `offset` ("" if none).
///
/// Tables opened by a header (`[[groups]]`) are spanned by the header only, so every branch is
/// searched, not only those whose span contains the offset.
fn path_at(root: &Spanned<DeTable<'_>>, offset: usize) -> String {
    fn contains(span: &Range<usize>, offset: usize) -> bool {
        span.contains(&offset) || (span.is_empty() && span.start == offset)
    }
    fn visit(value: &DeValue<'_>, path: &str, depth: usize, offset: usize) -> (usize, String) {
        let mut best = (0, String::new());
        let mut consider = |found: (usize, String)| {
            if found.0 > best.0 {
                best = found;
            }
        };
        if let Some(table) = value.as_table() {
            for (key, child) in table.iter() {
                let child_path = super::raw::join(path, key.get_ref());
                if contains(&key.span(), offset) || contains(&child.span(), offset) {
                    consider((depth + 1, child_path.clone()));
                }
                consider(visit(child.get_ref(), &child_path, depth + 1, offset));
            }
        } else if let Some(array) = value.as_array() {
            for (i, child) in array.iter().enumerate() {
                let child_path = format!("{path}[{i}]");
                if contains(&child.span(), offset) {
                    consider((depth + 1, child_path.clone()));
                }
                consider(visit(child.get_ref(), &child_path, depth + 1, offset));
            }
        }
        best
    }
    visit(&DeValue::Table(root.get_ref().clone()), "", 0, offset).1
}

// ---------------------------------------------------------------------------------------------
// Rules
// ---------------------------------------------------------------------------------------------

/// `[a, b]` with the shortest exact float formatting.
fn show(p: &[f32]) -> String {
    let items: Vec<String> = p.iter().map(|v| v.to_string()).collect();
    format!("[{}]", items.join(", "))
}

fn world_text(world: &World) -> String {
    format!("{}..{}", show(world.min()), show(world.max()))
}

fn finite_all(p: &[f32], path: &str) -> std::result::Result<(), Problem> {
    if p.iter().all(|v| v.is_finite()) {
        Ok(())
    } else {
        Err(Problem::new(
            path,
            format!("expected finite numbers, found {}", show(p)),
        ))
    }
}

/// `p` has `dim` finite numbers inside the world.
fn inside(world: &World, p: &[f32], path: &str, what: &str) -> std::result::Result<(), Problem> {
    if p.len() != world.dim() {
        return Err(Problem::new(
            path,
            format!(
                "expected {} numbers {}, found {}",
                world.dim(),
                if world.dim() == 2 {
                    "[x, y]"
                } else {
                    "[x, y, z]"
                },
                p.len()
            ),
        ));
    }
    finite_all(p, path)?;
    if world.contains(p) {
        Ok(())
    } else {
        Err(Problem::new(
            path,
            format!(
                "{what} {} lies outside the world {}",
                show(p),
                world_text(world)
            ),
        ))
    }
}

/// A strictly positive, finite length no larger than the coordinate range.
fn positive(v: f32, path: &str) -> std::result::Result<(), Problem> {
    if v.is_finite() && v > 0.0 && v <= MAX_COORD {
        Ok(())
    } else {
        Err(Problem::new(
            path,
            format!("expected a positive number (at most {MAX_COORD}), found {v}"),
        ))
    }
}

/// Every rule of a scenario, then its sanity checks ([`sanity::check`]): the first problem,
/// or the warnings; a problem's path is the field's path in the file.
pub(crate) fn validate(s: &Scenario) -> std::result::Result<Vec<Finding>, Problem> {
    steps_rule(s.steps, "steps")?;
    validate_world(&s.world)?;
    if s.outputs.every == 0 {
        return Err(Problem::new(
            "outputs.every",
            "expected at least 1 (record every N steps), found 0",
        ));
    }
    let objects = validate_objects(s)?;
    validate_groups(s, &objects)?;
    validate_events(s, &objects)?;
    sanity::check(s)
}

fn validate_world(world: &World) -> std::result::Result<(), Problem> {
    for (field, p) in [("world.min", world.min()), ("world.max", world.max())] {
        finite_all(p, field)?;
        if p.iter().any(|v| v.abs() > MAX_COORD) {
            return Err(Problem::new(
                field,
                format!(
                    "coordinates must lie within ±{MAX_COORD} (the controllers' range), found {}",
                    show(p)
                ),
            ));
        }
    }
    let axes = ["x", "y", "z"];
    for (i, (lo, hi)) in world.min().iter().zip(world.max()).enumerate() {
        if lo >= hi {
            return Err(Problem::new(
                "world.max",
                format!(
                    "expected `max` greater than `min` on every axis, but on {} max {hi} <= min {lo}",
                    axes[i]
                ),
            ));
        }
    }
    Ok(())
}

/// Checks the objects; returns the index of each name.
fn validate_objects(s: &Scenario) -> std::result::Result<HashMap<&str, usize>, Problem> {
    if s.objects.len() > usize::from(u16::MAX) {
        return Err(Problem::new(
            "objects",
            format!(
                "at most {} objects (ids are 16-bit), found {}",
                u16::MAX,
                s.objects.len()
            ),
        ));
    }
    let mut names: HashMap<&str, usize> = HashMap::new();
    let mut orders: HashMap<u32, usize> = HashMap::new();
    for (i, o) in s.objects.iter().enumerate() {
        let path = format!("objects[{i}]");
        if o.name.is_empty() {
            return Err(Problem::new(
                format!("{path}.name"),
                "expected a non-empty name",
            ));
        }
        if let Some(j) = names.insert(&o.name, i) {
            return Err(Problem::new(
                format!("{path}.name"),
                format!(
                    "duplicate object name `{}` (also objects[{j}]); names must be unique",
                    o.name
                ),
            ));
        }
        if o.kind.dim() != s.world.dim() {
            return Err(Problem::new(
                format!("{path}.kind"),
                format!(
                    "a `{}` belongs in a {}D world ({}), but this world is {}D",
                    o.kind.tag(),
                    o.kind.dim(),
                    if o.kind.dim() == 2 { "ants" } else { "bees" },
                    s.world.dim()
                ),
            ));
        }
        validate_geometry(&s.world, o, &path)?;
        if let ObjectKind::Waypoint { order, .. } = o.kind
            && let Some(j) = orders.insert(order, i)
        {
            return Err(Problem::new(
                format!("{path}.order"),
                format!(
                    "way point order {order} is also used by objects[{j}]; orders must be unique"
                ),
            ));
        }
    }
    Ok(names)
}

fn validate_geometry(world: &World, o: &Object, path: &str) -> std::result::Result<(), Problem> {
    let field = |f: &str| format!("{path}.{f}");
    match &o.kind {
        ObjectKind::Nest { center, radius }
        | ObjectKind::Rock { center, radius }
        | ObjectKind::Disturbance { center, radius }
        | ObjectKind::Waypoint { center, radius, .. } => {
            inside(world, center, &field("center"), "the centre")?;
            positive(*radius, &field("radius"))
        }
        ObjectKind::Food {
            center,
            radius,
            amount,
        } => {
            inside(world, center, &field("center"), "the centre")?;
            positive(*radius, &field("radius"))?;
            if *amount == Some(0) {
                return Err(Problem::new(
                    field("amount"),
                    "expected at least 1 unit of food (leave `amount` out for an endless source)",
                ));
            }
            Ok(())
        }
        ObjectKind::Sphere { center, radius } => {
            inside(world, center, &field("center"), "the centre")?;
            positive(*radius, &field("radius"))
        }
        ObjectKind::Target {
            center,
            radius,
            particles,
        } => {
            inside(world, center, &field("center"), "the centre")?;
            positive(*radius, &field("radius"))?;
            if !(1..=MAX_TARGET_PARTICLES).contains(particles) {
                return Err(Problem::new(
                    field("particles"),
                    format!(
                        "expected 1 to {MAX_TARGET_PARTICLES} virtual particles, found {particles}"
                    ),
                ));
            }
            Ok(())
        }
        ObjectKind::Box { min, max } => {
            inside(world, min, &field("min"), "the corner")?;
            inside(world, max, &field("max"), "the corner")?;
            if min.iter().zip(max).any(|(lo, hi)| lo >= hi) {
                return Err(Problem::new(
                    field("max"),
                    format!(
                        "expected `max` greater than `min` on every axis, found min {} max {}",
                        show(min),
                        show(max)
                    ),
                ));
            }
            Ok(())
        }
        ObjectKind::Shaft {
            center,
            radius,
            y_min,
            y_max,
        } => {
            finite_all(center, &field("center"))?;
            let (lo, hi) = (world.min(), world.max());
            if center[0] < lo[0] || center[0] > hi[0] || center[1] < lo[2] || center[1] > hi[2] {
                return Err(Problem::new(
                    field("center"),
                    format!(
                        "the axis [x, z] = {} lies outside the world's x range {}..{} or z \
                         range {}..{}",
                        show(center),
                        lo[0],
                        hi[0],
                        lo[2],
                        hi[2]
                    ),
                ));
            }
            positive(*radius, &field("radius"))?;
            for (v, f) in [(y_min, "y_min"), (y_max, "y_max")] {
                if !v.is_finite() || *v < lo[1] || *v > hi[1] {
                    return Err(Problem::new(
                        field(f),
                        format!(
                            "expected a height inside the world's y range {}..{}, found {v}",
                            lo[1], hi[1]
                        ),
                    ));
                }
            }
            if y_min >= y_max {
                return Err(Problem::new(
                    field("y_max"),
                    format!("expected `y_max` greater than `y_min` = {y_min}, found {y_max}"),
                ));
            }
            Ok(())
        }
        ObjectKind::Polygon { points } => {
            if points.len() < 3 {
                return Err(Problem::new(
                    field("points"),
                    format!(
                        "a polygon needs at least 3 points [x, y], found {}",
                        points.len()
                    ),
                ));
            }
            for (k, p) in points.iter().enumerate() {
                inside(world, p, &format!("{path}.points[{k}]"), "the point")?;
            }
            simple_polygon(points).map_err(|m| Problem::new(field("points"), m))
        }
    }
}

/// `Ok` when the closed polygon has no repeated consecutive points, no two non-adjacent edges
/// touching or crossing, and a non-zero area.
fn simple_polygon(points: &[[f32; 2]]) -> std::result::Result<(), String> {
    let n = points.len();
    let p = |i: usize| {
        let [x, y] = points[i % n];
        [f64::from(x), f64::from(y)]
    };
    for i in 0..n {
        if p(i) == p(i + 1) {
            return Err(format!(
                "points {i} and {} are the same point; a polygon's points must differ",
                (i + 1) % n
            ));
        }
    }
    let cross = |o: [f64; 2], a: [f64; 2], b: [f64; 2]| {
        (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0])
    };
    let on_segment = |a: [f64; 2], b: [f64; 2], q: [f64; 2]| {
        q[0] >= a[0].min(b[0])
            && q[0] <= a[0].max(b[0])
            && q[1] >= a[1].min(b[1])
            && q[1] <= a[1].max(b[1])
    };
    let intersects = |a: [f64; 2], b: [f64; 2], c: [f64; 2], d: [f64; 2]| {
        let (d1, d2) = (cross(c, d, a), cross(c, d, b));
        let (d3, d4) = (cross(a, b, c), cross(a, b, d));
        if ((d1 > 0.0 && d2 < 0.0) || (d1 < 0.0 && d2 > 0.0))
            && ((d3 > 0.0 && d4 < 0.0) || (d3 < 0.0 && d4 > 0.0))
        {
            return true;
        }
        (d1 == 0.0 && on_segment(c, d, a))
            || (d2 == 0.0 && on_segment(c, d, b))
            || (d3 == 0.0 && on_segment(a, b, c))
            || (d4 == 0.0 && on_segment(a, b, d))
    };
    for i in 0..n {
        for j in i + 1..n {
            let adjacent = j == i + 1 || (i == 0 && j == n - 1);
            if adjacent {
                continue;
            }
            if intersects(p(i), p(i + 1), p(j), p(j + 1)) {
                return Err(format!(
                    "the polygon is not simple: edge {i} (points {i}-{}) touches or crosses \
                     edge {j} (points {j}-{})",
                    (i + 1) % n,
                    (j + 1) % n
                ));
            }
        }
    }
    let area2: f64 = (0..n)
        .map(|i| p(i)[0] * p(i + 1)[1] - p(i + 1)[0] * p(i)[1])
        .sum();
    if area2 == 0.0 {
        return Err("the polygon has zero area (its points are collinear)".to_owned());
    }
    Ok(())
}

/// The object `name` refers to, or a problem at `path` listing the names there are.
fn lookup<'s>(
    s: &'s Scenario,
    objects: &HashMap<&str, usize>,
    name: &str,
    path: &str,
) -> std::result::Result<(usize, &'s Object), Problem> {
    match objects.get(name) {
        Some(&i) => Ok((i, &s.objects[i])),
        None => {
            let mut known: Vec<&str> = s.objects.iter().map(|o| o.name.as_str()).collect();
            known.sort_unstable();
            Err(Problem::new(
                path,
                if known.is_empty() {
                    format!("no object named `{name}`: the scenario has no objects")
                } else {
                    format!("no object named `{name}` (objects: {})", known.join(", "))
                },
            ))
        }
    }
}

fn validate_groups(
    s: &Scenario,
    objects: &HashMap<&str, usize>,
) -> std::result::Result<(), Problem> {
    if s.groups.is_empty() {
        return Err(Problem::new(
            "groups",
            "a scenario needs at least one group of agents (a [[groups]] table)",
        ));
    }
    let mut names: HashMap<&str, usize> = HashMap::new();
    let mut total: u64 = 0;
    for (i, g) in s.groups.iter().enumerate() {
        let path = format!("groups[{i}]");
        let field = |f: &str| format!("{path}.{f}");
        if g.name.is_empty() {
            return Err(Problem::new(field("name"), "expected a non-empty name"));
        }
        if let Some(j) = names.insert(&g.name, i) {
            return Err(Problem::new(
                field("name"),
                format!(
                    "duplicate group name `{}` (also groups[{j}]); names must be unique",
                    g.name
                ),
            ));
        }
        if g.count == 0 || g.count > MAX_AGENTS {
            return Err(Problem::new(
                field("count"),
                format!("expected 1 to {MAX_AGENTS} agents, found {}", g.count),
            ));
        }
        total += u64::from(g.count);
        if total > u64::from(MAX_AGENTS) {
            return Err(Problem::new(
                field("count"),
                format!(
                    "the groups hold {total} agents in all, more than the {MAX_AGENTS} a \
                     scenario may have"
                ),
            ));
        }
        if g.model != s.world.model() {
            return Err(Problem::new(
                field("model"),
                format!(
                    "`{}` groups live in a {} world, but this world is {}D (`dim = {}`)",
                    g.model.as_str(),
                    if g.model == Model::Ant {
                        "2D (`dim = 2`)"
                    } else {
                        "3D (`dim = 3`)"
                    },
                    s.world.dim(),
                    s.world.dim()
                ),
            ));
        }
        match g.model {
            Model::Ant => validate_ant_group(s, objects, g, &path)?,
            Model::Bee => validate_bee_group(s, objects, g, &path)?,
        }
        validate_spawn(s, objects, g, &path)?;
    }
    Ok(())
}

fn validate_ant_group(
    s: &Scenario,
    objects: &HashMap<&str, usize>,
    g: &Group,
    path: &str,
) -> std::result::Result<(), Problem> {
    let field = |f: &str| format!("{path}.{f}");
    let Some(nest) = &g.nest else {
        return Err(Problem::new(
            field("nest"),
            "missing field `nest`: an ant group needs the name of its home nest (an object of \
             kind `nest`)",
        ));
    };
    let (_, o) = lookup(s, objects, nest, &field("nest"))?;
    if !matches!(o.kind, ObjectKind::Nest { .. }) {
        return Err(Problem::new(
            field("nest"),
            format!(
                "`{nest}` is a `{}`, expected an object of kind `nest`",
                o.kind.tag()
            ),
        ));
    }
    if g.goal.is_some() {
        return Err(Problem::new(
            field("goal"),
            "`goal` is for bee groups; ants forage between their `nest` and the food sources",
        ));
    }
    if g.bee.is_some() {
        return Err(Problem::new(
            field("bee"),
            "bee parameters in an ant group; use `[groups.ant]` for ant parameters",
        ));
    }
    let params = g.ant_params();
    check_params(
        &params,
        || params.cast::<Fx>().validate(),
        g.scalar,
        path,
        "ant",
    )
}

/// Checks a group's parameters, and for a fixed-point group also `in_fixed` (the same
/// parameters converted to `Fx`); the problem names the first bad one and what it takes (from
/// the model's parameter table in swarm-core).
fn check_params<P: ModelParams>(
    params: &P,
    in_fixed: impl FnOnce() -> swarm_core::Result<()>,
    scalar: ScalarType,
    path: &str,
    model: &str,
) -> std::result::Result<(), Problem> {
    let checked = params.validate().and_then(|()| match scalar {
        ScalarType::Fixed => in_fixed(),
        ScalarType::F32 => Ok(()),
    });
    let Err(e) = checked else {
        return Ok(());
    };
    let field = match e {
        swarm_core::Error::BadParam { field } => field,
        _ => "?",
    };
    let takes = match P::index_of(field) {
        Some(i) => P::SPECS[i].to_string(),
        None => format!("a value `{model}` parameters accept"),
    };
    Err(Problem::new(
        format!("{path}.{model}.{field}"),
        format!("invalid {model} parameter `{field}`: expected {takes}"),
    ))
}

fn validate_bee_group(
    s: &Scenario,
    objects: &HashMap<&str, usize>,
    g: &Group,
    path: &str,
) -> std::result::Result<(), Problem> {
    let field = |f: &str| format!("{path}.{f}");
    if g.nest.is_some() {
        return Err(Problem::new(
            field("nest"),
            "`nest` is for ant groups; bees fly toward a `goal` (an object of kind `target`)",
        ));
    }
    if let Some(goal) = &g.goal {
        let (_, o) = lookup(s, objects, goal, &field("goal"))?;
        if !matches!(o.kind, ObjectKind::Target { .. }) {
            return Err(Problem::new(
                field("goal"),
                format!(
                    "`{goal}` is a `{}`, expected an object of kind `target`",
                    o.kind.tag()
                ),
            ));
        }
    }
    if g.ant.is_some() {
        return Err(Problem::new(
            field("ant"),
            "ant parameters in a bee group; use `[groups.bee]` for bee parameters",
        ));
    }
    let params = g.bee_params();
    check_params(
        &params,
        || params.cast::<Fx>().validate(),
        g.scalar,
        path,
        "bee",
    )
}

fn validate_spawn(
    s: &Scenario,
    objects: &HashMap<&str, usize>,
    g: &Group,
    path: &str,
) -> std::result::Result<(), Problem> {
    let field = |f: &str| format!("{path}.spawn.{f}");
    let world = &s.world;
    match &g.spawn.region {
        SpawnRegion::Around { at, radius } => {
            let (_, o) = lookup(s, objects, at, &field("at"))?;
            let Some(center) = o.kind.point() else {
                return Err(Problem::new(
                    field("at"),
                    format!(
                        "cannot spawn around `{at}`: a `{}` has no centre point (spawn around a \
                         nest, food source, target, ... or in a box with `min` + `max`)",
                        o.kind.tag()
                    ),
                ));
            };
            positive(*radius, &field("radius"))?;
            let fits = center
                .iter()
                .zip(world.min().iter().zip(world.max()))
                .all(|(c, (lo, hi))| c - radius >= *lo && c + radius <= *hi);
            if !fits {
                return Err(Problem::new(
                    field("radius"),
                    format!(
                        "the {} of radius {radius} around `{at}` (centre {}) reaches outside the \
                         world {}",
                        if world.dim() == 2 { "disc" } else { "ball" },
                        show(center),
                        world_text(world)
                    ),
                ));
            }
        }
        SpawnRegion::Box { min, max } => {
            inside(world, min, &field("min"), "the corner")?;
            inside(world, max, &field("max"), "the corner")?;
            if min.iter().zip(max).any(|(lo, hi)| lo > hi) {
                return Err(Problem::new(
                    field("max"),
                    format!(
                        "expected `max` >= `min` on every axis, found min {} max {}",
                        show(min),
                        show(max)
                    ),
                ));
            }
        }
    }
    if let Some(h) = &g.spawn.heading {
        let path = field("heading");
        if h.len() != world.dim() {
            return Err(Problem::new(
                path,
                format!(
                    "expected a direction of {} numbers, found {}",
                    world.dim(),
                    h.len()
                ),
            ));
        }
        finite_all(h, &path)?;
        if h.iter().all(|v| *v == 0.0) {
            return Err(Problem::new(
                path,
                "expected a non-zero direction (leave `heading` out for random headings)",
            ));
        }
    }
    Ok(())
}

fn validate_events(
    s: &Scenario,
    objects: &HashMap<&str, usize>,
) -> std::result::Result<(), Problem> {
    let mut active: Vec<bool> = s.objects.iter().map(|o| o.active).collect();
    let mut previous: Option<(u32, usize)> = None;
    for (i, e) in s.events.iter().enumerate() {
        let path = format!("events[{i}]");
        let field = |f: &str| format!("{path}.{f}");
        if e.step >= s.steps {
            return Err(Problem::new(
                field("step"),
                format!(
                    "expected a step before the end of the run (`steps` = {}), found {}",
                    s.steps, e.step
                ),
            ));
        }
        if let Some((step, j)) = previous
            && e.step < step
        {
            return Err(Problem::new(
                field("step"),
                format!(
                    "events must be listed in step order, but step {} comes after step {step} \
                     (events[{j}])",
                    e.step
                ),
            ));
        }
        previous = Some((e.step, i));
        let verb = e.action.verb();
        let name = e.action.object();
        let name_path = if verb == "move" {
            field("move.object")
        } else {
            field(verb)
        };
        let (k, o) = lookup(s, objects, name, &name_path)?;
        let step = e.step;
        match &e.action {
            Action::Add(_) if active[k] => {
                return Err(Problem::new(
                    name_path,
                    format!(
                        "`{name}` is already present at step {step} (objects are present from \
                         the start unless `active = false`)"
                    ),
                ));
            }
            Action::Remove(_) if !active[k] => {
                return Err(Problem::new(
                    name_path,
                    format!("`{name}` is not present at step {step}, so it cannot be removed"),
                ));
            }
            Action::Add(_) | Action::Remove(_) => active[k] = !active[k],
            Action::Start(_) | Action::Stop(_) => {
                if !matches!(o.kind, ObjectKind::Disturbance { .. }) {
                    return Err(Problem::new(
                        name_path,
                        format!(
                            "`{verb}` applies to disturbances, but `{name}` is a `{}` (use \
                             `add` / `remove`)",
                            o.kind.tag()
                        ),
                    ));
                }
                let start = matches!(e.action, Action::Start(_));
                if active[k] == start {
                    return Err(Problem::new(
                        name_path,
                        if start {
                            format!(
                                "`{name}` is already acting at step {step} (a disturbance acts \
                                 from the start unless `active = false`)"
                            )
                        } else {
                            format!("`{name}` is not acting at step {step}, so it cannot stop")
                        },
                    ));
                }
                active[k] = start;
            }
            Action::Move { to, .. } => {
                let Some(center) = o.kind.center() else {
                    return Err(Problem::new(
                        name_path,
                        format!(
                            "`{name}` is a `{}`, which has no centre to move",
                            o.kind.tag()
                        ),
                    ));
                };
                let to_path = field("move.to");
                if to.len() != center.len() {
                    return Err(Problem::new(
                        to_path,
                        format!(
                            "expected {} numbers (like the `center` of the `{}` `{name}`), \
                             found {}",
                            center.len(),
                            o.kind.tag(),
                            to.len()
                        ),
                    ));
                }
                finite_all(to, &to_path)?;
                let mut moved = o.clone();
                moved.kind.set_center(to);
                validate_geometry(&s.world, &moved, "")
                    .map_err(|p| Problem::new(to_path, format!("after the move: {}", p.message)))?;
            }
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn path_segments() {
        assert_eq!(
            segments("groups[1].spawn.radius"),
            vec![
                Seg::Key("groups"),
                Seg::Index(1),
                Seg::Key("spawn"),
                Seg::Key("radius")
            ]
        );
        assert_eq!(
            segments("objects[2].points[3]"),
            vec![
                Seg::Key("objects"),
                Seg::Index(2),
                Seg::Key("points"),
                Seg::Index(3)
            ]
        );
        assert!(segments("").is_empty());
    }

    #[test]
    fn simple_polygons() {
        assert!(simple_polygon(&[[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]]).is_ok());
        // A bow tie crosses itself.
        assert!(simple_polygon(&[[0.0, 0.0], [1.0, 1.0], [1.0, 0.0], [0.0, 1.0]]).is_err());
        assert!(simple_polygon(&[[0.0, 0.0], [1.0, 1.0], [2.0, 2.0]]).is_err());
        assert!(simple_polygon(&[[0.0, 0.0], [0.0, 0.0], [2.0, 2.0]]).is_err());
    }
}
