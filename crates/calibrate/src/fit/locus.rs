//! The realisable chromaticities: the convex hull of the spectral locus of the observer the
//! measurements' XYZ are under (CIE 1931 for an instrument's XYZ), 380–780 nm at 1 nm. Every light is a mixture of
//! monochromatic ones, so its chromaticity lies in that hull (the locus closed by the purple
//! line); a fitted primary outside it is physically impossible. The fit moves such a primary
//! onto the hull's nearest point (its luminance kept) and says so.

use specpoly_core::Observer;

/// The hull's vertices (x, y) under `observer`, counter-clockwise (Andrew's monotone chain).
pub fn hull(observer: Observer) -> Vec<[f64; 2]> {
    let mut p: Vec<[f64; 2]> = observer
        .table()
        .iter()
        .filter_map(|c| {
            let c = c.map(f64::from);
            let s = c[0] + c[1] + c[2];
            (s > 1e-9).then(|| [c[0] / s, c[1] / s])
        })
        .collect();
    p.sort_by(|a, b| a[0].total_cmp(&b[0]).then(a[1].total_cmp(&b[1])));
    p.dedup();
    let cross = |o: [f64; 2], a: [f64; 2], b: [f64; 2]| {
        (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0])
    };
    let mut h: Vec<[f64; 2]> = Vec::new();
    for pass in 0..2 {
        let start = h.len();
        let it: Box<dyn Iterator<Item = &[f64; 2]>> = if pass == 0 {
            Box::new(p.iter())
        } else {
            Box::new(p.iter().rev())
        };
        for &q in it {
            while h.len() >= start + 2 && cross(h[h.len() - 2], h[h.len() - 1], q) <= 0.0 {
                h.pop();
            }
            h.push(q);
        }
        h.pop();
    }
    h
}

/// Whether `xy` lies inside the counter-clockwise hull `h` (or on it, within `1e-12`).
pub fn inside(h: &[[f64; 2]], xy: [f64; 2]) -> bool {
    (0..h.len()).all(|i| {
        let (a, b) = (h[i], h[(i + 1) % h.len()]);
        (b[0] - a[0]) * (xy[1] - a[1]) - (b[1] - a[1]) * (xy[0] - a[0]) >= -1e-12
    })
}

/// The point of the hull `h` nearest `xy`, moved `1e-6` toward the hull's centre (so that it
/// tests inside after rounding).
pub fn nearest(h: &[[f64; 2]], xy: [f64; 2]) -> [f64; 2] {
    let mut best = (f64::INFINITY, xy);
    for i in 0..h.len() {
        let (a, b) = (h[i], h[(i + 1) % h.len()]);
        let d = [b[0] - a[0], b[1] - a[1]];
        let l2 = d[0] * d[0] + d[1] * d[1];
        let t = if l2 > 0.0 {
            (((xy[0] - a[0]) * d[0] + (xy[1] - a[1]) * d[1]) / l2).clamp(0.0, 1.0)
        } else {
            0.0
        };
        let q = [a[0] + t * d[0], a[1] + t * d[1]];
        let e = (q[0] - xy[0]).powi(2) + (q[1] - xy[1]).powi(2);
        if e < best.0 {
            best = (e, q);
        }
    }
    let n = h.len() as f64;
    let c = [
        h.iter().map(|p| p[0]).sum::<f64>() / n,
        h.iter().map(|p| p[1]).sum::<f64>() / n,
    ];
    let q = best.1;
    let d = ((c[0] - q[0]).powi(2) + (c[1] - q[1]).powi(2)).sqrt();
    if d > 0.0 {
        [
            q[0] + 1e-6 * (c[0] - q[0]) / d,
            q[1] + 1e-6 * (c[1] - q[1]) / d,
        ]
    } else {
        q
    }
}

/// Moves primaries (columns, XYZ) whose chromaticity is outside the hull onto it, keeping
/// their luminance; one sentence per primary moved.
pub fn constrain(p: &mut [[f64; 3]; 3], observer: Observer) -> Vec<String> {
    const NAMES: [&str; 3] = ["red", "green", "blue"];
    let h = hull(observer);
    let mut notes = Vec::new();
    for c in 0..3 {
        let s = p[c][0] + p[c][1] + p[c][2];
        if !(s > 0.0 && p[c][1] > 0.0) {
            continue;
        }
        let xy = [p[c][0] / s, p[c][1] / s];
        if inside(&h, xy) {
            continue;
        }
        let q = nearest(&h, xy);
        let y = p[c][1];
        p[c] = [q[0] * y / q[1], y, (1.0 - q[0] - q[1]) * y / q[1]];
        notes.push(format!(
            "the fitted {} primary x = {:.4}, y = {:.4} is outside the spectral locus ({}): moved to its nearest point, x = {:.4}, y = {:.4}",
            NAMES[c], xy[0], xy[1], observer.label(), q[0], q[1]
        ));
    }
    notes
}
