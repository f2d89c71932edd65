//! Diagnostics: where in the TOML text a problem lies. A [`Document`] is the parsed text; it
//! turns the parser's and the deserializer's errors (which carry a byte span) and the checks'
//! problems (which carry a field path) into [`Diagnostic`]s naming the file, the line, the
//! column and the field path.

use std::ops::Range;

use serde::Deserialize;
use toml::Spanned;
use toml::de::{DeTable, DeValue};

use super::diagnostic::{Diagnostic, DiagnosticKind};
use super::problem::{Problem, join};
use crate::{Result, SimError};

/// Scenario text, parsed into a TOML document that keeps every key's and value's span.
pub(crate) struct Document<'a> {
    text: &'a str,
    origin: &'a str,
    tree: Spanned<DeTable<'a>>,
}

impl<'a> Document<'a> {
    /// Parses `text`; diagnostics name it `origin`. A syntax error is reported at the parser's
    /// position, with the path of the field there.
    pub(crate) fn parse(text: &'a str, origin: &'a str) -> Result<Self> {
        match DeTable::parse(text) {
            Ok(tree) => Ok(Document { text, origin, tree }),
            Err(e) => {
                let (partial, _) = DeTable::parse_recoverable(text);
                let field = e
                    .span()
                    .map(|s| path_at(&partial, s.start))
                    .unwrap_or_default();
                Err(invalid(diagnostic(
                    text,
                    origin,
                    DiagnosticKind::Syntax,
                    e.span(),
                    field,
                    e.message().to_owned(),
                )))
            }
        }
    }

    /// The document read into `T` by serde. A shape error (an unknown field, a wrong type, a
    /// missing field) is reported at the deserializer's span, its field path found through the
    /// document; a missing field is reported at its table, with what it holds.
    pub(crate) fn deserialize<T: Deserialize<'a>>(&self) -> Result<T> {
        T::deserialize(toml::de::Deserializer::from(self.tree.clone())).map_err(|e| {
            // A missing field is reported at its table (the whole document: an empty span at 0).
            let table = match e.span() {
                Some(s) if s.is_empty() && s.start == 0 => String::new(),
                Some(s) => path_at(&self.tree, s.start),
                None => String::new(),
            };
            let field = match missing_field(e.message()) {
                Some(name) => join(&table, name),
                None => table,
            };
            let mut message = e.message().to_owned();
            if let Some(hint) = missing_field(&message).and_then(hint) {
                message = format!("{message}: expected {hint}");
            }
            invalid(self.diagnostic(DiagnosticKind::Shape, e.span(), field, message))
        })
    }

    /// `problem` as a diagnostic at its field in the text (the nearest enclosing table when the
    /// field itself is missing).
    pub(crate) fn locate(&self, kind: DiagnosticKind, problem: Problem) -> Diagnostic {
        let span = span_of(&self.tree, &problem.path);
        self.diagnostic(kind, span, problem.path, problem.message)
    }

    fn diagnostic(
        &self,
        kind: DiagnosticKind,
        span: Option<Range<usize>>,
        field: String,
        message: String,
    ) -> Diagnostic {
        diagnostic(self.text, self.origin, kind, span, field, message)
    }
}

/// `problem` as a diagnostic without a line (a scenario built in code, a command-line option),
/// naming `file`.
pub(crate) fn unlocated(file: String, kind: DiagnosticKind, problem: Problem) -> Diagnostic {
    Diagnostic {
        kind,
        file,
        line: None,
        column: None,
        field: problem.path,
        message: problem.message,
        source_line: None,
    }
}

/// The error of a rejected scenario.
pub(crate) fn invalid(diagnostic: Diagnostic) -> SimError {
    SimError::InvalidScenario(Box::new(diagnostic))
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
pub(crate) fn path_at(root: &Spanned<DeTable<'_>>, offset: usize) -> String {
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
        // Each child: its path, the span of its key (none in an array) and its value.
        let children = if let Some(table) = value.as_table() {
            table
                .iter()
                .map(|(key, child)| (join(path, key.get_ref()), Some(key.span()), child))
                .collect::<Vec<_>>()
        } else if let Some(array) = value.as_array() {
            array
                .iter()
                .enumerate()
                .map(|(i, child)| (format!("{path}[{i}]"), None, child))
                .collect()
        } else {
            Vec::new()
        };
        for (child_path, key, child) in children {
            if key.is_some_and(|k| contains(&k, offset)) || contains(&child.span(), offset) {
                consider((depth + 1, child_path.clone()));
            }
            consider(visit(child.get_ref(), &child_path, depth + 1, offset));
        }
        best
    }
    visit(&DeValue::Table(root.get_ref().clone()), "", 0, offset).1
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn path_segments() {
        use Seg::{Index, Key};
        for (path, segs) in [
            (
                "groups[1].spawn.radius",
                vec![Key("groups"), Index(1), Key("spawn"), Key("radius")],
            ),
            (
                "objects[2].points[3]",
                vec![Key("objects"), Index(2), Key("points"), Index(3)],
            ),
        ] {
            assert_eq!(segments(path), segs);
        }
        assert!(segments("").is_empty());
    }
}
