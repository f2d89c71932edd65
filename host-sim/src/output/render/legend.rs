//! The legend (agent colours and object kinds, with names) and the step number.

use super::ColorBy;
use super::canvas::Canvas;
use super::font::text_width;
use super::palette::{I_BORDER, I_INK, I_PAPER, agent_index, kind_index};
use crate::output::frames::{Frame, label_name};
use crate::output::scene::{Scene, ShapeKind};

/// Legend: agent colour swatches then object kinds present, with names, in a box at top left;
/// the step at the top right.
pub(super) fn draw_legend(
    canvas: &mut Canvas,
    scene: &Scene,
    frame: &Frame,
    by: ColorBy,
    scale: i64,
) {
    let mut entries: Vec<(String, u8, bool)> = Vec::new();
    let mut used = [false; 8];
    let mut used_codes: Vec<u16> = Vec::new();
    for a in &frame.agents {
        let code = if by == ColorBy::Group {
            a.group
        } else {
            u16::from(a.label)
        };
        if !used[code as usize % 8] {
            used[code as usize % 8] = true;
            used_codes.push(code);
        }
    }
    if by == ColorBy::Label && used_codes.iter().all(|&c| c < 3) {
        // Ant labels only: show all three, used or not.
        used_codes = vec![0, 1, 2];
    }
    used_codes.sort_unstable();
    for code in used_codes {
        let name = if by == ColorBy::Group {
            format!("group {code}")
        } else {
            format!("label: {}", label_name(code as u8))
        };
        entries.push((name, agent_index(by, code as u8, code, 0), false));
    }
    for k in ShapeKind::ALL {
        if scene.shapes.iter().any(|s| s.kind == k) {
            let ring = matches!(k, ShapeKind::Disturbance | ShapeKind::Waypoint);
            let name = match k {
                ShapeKind::Food => "food source".to_owned(),
                // Ant rocks and polygons, bee boxes (the grassland's ground among them).
                ShapeKind::Rock => "obstacle".to_owned(),
                _ => serde_json::to_value(k)
                    .ok()
                    .and_then(|v| v.as_str().map(str::to_owned))
                    .unwrap_or_default(),
            };
            entries.push((name, kind_index(k), ring));
        }
    }
    let pad = 3 * scale;
    let sw = 5 * scale; // swatch size = text height
    let line_h = 5 * scale + 2 * scale;
    let text_w = entries
        .iter()
        .map(|e| text_width(&e.0, scale))
        .max()
        .unwrap_or(0);
    let (x0, y0) = (canvas.w as i64 / 60 + 2, canvas.w as i64 / 60 + 2);
    if !entries.is_empty() {
        let bw = pad * 2 + sw + 2 * scale + text_w;
        let bh = pad * 2 + line_h * entries.len() as i64 - 2 * scale;
        canvas.rect(x0, y0, x0 + bw, y0 + bh, I_PAPER);
        canvas.rect_outline(x0, y0, x0 + bw, y0 + bh, I_BORDER);
        for (i, (name, c, ring)) in entries.iter().enumerate() {
            let y = y0 + pad + i as i64 * line_h;
            let x = x0 + pad;
            if *ring {
                canvas.rect_outline(x, y, x + sw - 1, y + sw - 1, *c);
                canvas.rect_outline(x + 1, y + 1, x + sw - 2, y + sw - 2, *c);
            } else {
                canvas.rect(x, y, x + sw - 1, y + sw - 1, *c);
            }
            canvas.text(x + sw + 2 * scale, y, name, scale, I_INK);
        }
    }
    draw_step(canvas, frame.step, scale);
}

pub(super) fn draw_step(canvas: &mut Canvas, step: u32, scale: i64) {
    let s = format!("step {step}");
    let w = text_width(&s, scale);
    let pad = 2 * scale;
    let x1 = canvas.w as i64 - canvas.w as i64 / 60 - 2;
    let y0 = canvas.w as i64 / 60 + 2;
    let x0 = x1 - w - 2 * pad;
    canvas.rect(x0, y0, x1, y0 + 5 * scale + 2 * pad, I_PAPER);
    canvas.text(x0 + pad, y0 + pad, &s, scale, I_INK);
}
