//! The `render --compare` image: the panels side by side, each under a label (the mode, and
//! for a ΔE00 map its mean), and below them a colour bar of the ΔE00 heat map
//! ([`crate::heat`], 0 to [`crate::HEAT_MAX`]) with tick labels. Text is drawn in the plots'
//! embedded font ([`specpoly_plot::draw_text`]), so it reads the same on every machine.

use crate::error::Result;
use specpoly_plot::{draw_text, measure_text};

/// One panel: its label and its RGB pixels.
pub struct Panel {
    /// The caption above it, e.g. `poly` or `ΔE00 rgb (mean 0.84)`.
    pub label: String,
    /// Width (px).
    pub width: u32,
    /// Height (px).
    pub height: u32,
    /// RGB, row-major.
    pub rgb: Vec<u8>,
}

/// Gap between panels (px, black).
const GAP: u32 = 4;

/// The text size for panels of height `h`: readable (≥ 10 px) on small renders, not huge on
/// large ones.
fn text_px(h: u32) -> f64 {
    (h as f64 / 14.0).clamp(10.0, 28.0)
}

/// Composes the panels (same height) with their labels and the ΔE00 colour bar; returns
/// `(width, height, rgb)`.
pub fn compose(panels: &[Panel]) -> Result<(u32, u32, Vec<u8>)> {
    let ph = panels.iter().map(|p| p.height).max().unwrap_or(0);
    let px = text_px(ph);
    let label_h = (px * 1.6).ceil() as u32;
    let bar_h = (px * 0.9).ceil() as u32;
    let ticks_h = (px * 1.6).ceil() as u32;
    let bottom = bar_h + ticks_h + (px * 0.6) as u32;
    let w: u32 =
        panels.iter().map(|p| p.width).sum::<u32>() + GAP * (panels.len() as u32).saturating_sub(1);
    let h = label_h + ph + bottom;
    let mut out = vec![255u8; (w * h * 3) as usize];
    // panels, black gaps
    for y in label_h..label_h + ph {
        let row = (y * w * 3) as usize;
        out[row..row + (w * 3) as usize].fill(0);
    }
    let mut x0 = 0u32;
    for p in panels {
        for y in 0..p.height {
            let src = &p.rgb[(y * p.width * 3) as usize..((y + 1) * p.width * 3) as usize];
            let at = (((label_h + y) * w + x0) * 3) as usize;
            out[at..at + src.len()].copy_from_slice(src);
        }
        // the label, centred over the panel, shrunk to its width if need be
        let mut size = px;
        while size > 8.0 && measure_text(&p.label, size) + 4 > p.width {
            size -= 0.5;
        }
        let tw = measure_text(&p.label, size);
        let tx = x0 as i32 + (p.width as i32 - tw as i32).max(0) / 2;
        draw_text(
            &mut out,
            (w, h),
            (tx, (px * 0.25) as i32),
            size,
            [0, 0, 0],
            &p.label,
        )?;
        x0 += p.width + GAP;
    }
    // the colour bar under the panels, full width less a margin for the end labels
    let name = "ΔE00";
    let margin = (measure_text(name, px * 0.85) + 8).min(w / 4);
    let (bx0, bx1) = (margin, w.saturating_sub(margin).max(margin + 1));
    let by0 = label_h + ph + (px * 0.4) as u32;
    for x in bx0..bx1 {
        let de = crate::HEAT_MAX * (x - bx0) as f64 / (bx1 - 1 - bx0).max(1) as f64;
        let c = crate::heat(de);
        for y in by0..by0 + bar_h {
            let i = ((y * w + x) * 3) as usize;
            out[i..i + 3].copy_from_slice(&c);
        }
    }
    // ticks every 2 ΔE00, then the bar's name
    let steps = 5;
    for k in 0..=steps {
        let v = crate::HEAT_MAX * k as f64 / steps as f64;
        let x = bx0 + ((bx1 - 1 - bx0) as f64 * k as f64 / steps as f64).round() as u32;
        for y in by0 + bar_h..by0 + bar_h + (px * 0.3) as u32 {
            if y < h {
                let i = ((y * w + x) * 3) as usize;
                out[i..i + 3].fill(0);
            }
        }
        let t = if k == steps {
            format!("≥{v}")
        } else {
            format!("{v}")
        };
        let tw = measure_text(&t, px * 0.85) as i32;
        draw_text(
            &mut out,
            (w, h),
            (x as i32 - tw / 2, (by0 + bar_h) as i32 + (px * 0.3) as i32),
            px * 0.85,
            [0, 0, 0],
            &t,
        )?;
    }
    draw_text(
        &mut out,
        (w, h),
        (2, by0 as i32 - (px * 0.1) as i32),
        px * 0.85,
        [0, 0, 0],
        name,
    )?;
    Ok((w, h, out))
}

/// The panels of a comparison: each mode of `shown`, labelled with its name, then the
/// reference, then each shown mode's ΔE00 heat map ([`crate::heat`]) labelled with its mean; the
/// images encoded for `out`.
pub fn comparison_panels(
    shown: &[&crate::ModeResult],
    reference: &crate::Image,
    out: &crate::Output,
) -> Vec<Panel> {
    let panel = |label: String, rgb: Vec<u8>| Panel {
        label,
        width: reference.width,
        height: reference.height,
        rgb,
    };
    let mut panels: Vec<Panel> = shown
        .iter()
        .map(|m| panel(m.repr.to_string(), crate::to_rgb8(&m.image, out)))
        .collect();
    panels.push(panel(
        "reference (1 nm)".into(),
        crate::to_rgb8(reference, out),
    ));
    panels.extend(shown.iter().map(|m| {
        panel(
            format!("ΔE00 {} (mean {:.2})", m.repr, m.stats.mean),
            m.delta_e.iter().flat_map(|d| crate::heat(*d)).collect(),
        )
    }));
    panels
}

#[cfg(test)]
mod tests {
    use super::*;

    fn panel(label: &str, c: u8) -> Panel {
        Panel {
            label: label.into(),
            width: 64,
            height: 48,
            rgb: vec![c; 64 * 48 * 3],
        }
    }

    #[test]
    fn labels_and_the_colour_bar_are_drawn() {
        let (w, h, px) = compose(&[panel("rgb", 128), panel("ΔE00 rgb (mean 1.2)", 128)]).unwrap();
        assert_eq!(w, 64 * 2 + GAP);
        assert!(h > 48 + 20);
        // the label strip has dark text pixels above each panel
        let dark_in = |x0: u32, x1: u32, y0: u32, y1: u32| {
            (y0..y1).any(|y| {
                (x0..x1).any(|x| {
                    let i = ((y * w + x) * 3) as usize;
                    px[i] < 100 && px[i + 1] < 100 && px[i + 2] < 100
                })
            })
        };
        let label_h = (text_px(48) * 1.6).ceil() as u32;
        assert!(dark_in(0, 64, 0, label_h), "first label");
        assert!(dark_in(64 + GAP, w, 0, label_h), "second label");
        // the bar runs from the heat map's black to its white
        let bar_y = label_h + 48 + (text_px(48) * 0.4) as u32 + 2;
        let row: Vec<[u8; 3]> = (0..w)
            .map(|x| {
                let i = ((bar_y * w + x) * 3) as usize;
                [px[i], px[i + 1], px[i + 2]]
            })
            .collect();
        assert!(row.contains(&super::super::heat(0.0)));
        let mut colours = row.clone();
        colours.sort();
        colours.dedup();
        assert!(colours.len() > 40, "a gradient: {} colours", colours.len());
    }
}
