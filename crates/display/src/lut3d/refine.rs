//! Node values fitted to the colours between the nodes.
//!
//! A consumer interpolates the LUT tetrahedrally between nodes; where the device values curve
//! inside a cell — near black, where a source curve's linear foot meets a display curve's power
//! law (device `∝ c^(1/γ)`), and where a model's curves or interaction bend — the interpolated
//! device values miss between nodes that are each exact. ArgyllCMS fits its tables to the
//! colours rather than sampling them (its `rspl` scattered-data fit); this module does the same
//! where it matters:
//!
//! 1. every cell's centre is interpolated and predicted through the model; cells whose colour
//!    there misses the source's by more than [`CELL_DE`] ΔE00 are *bad*;
//! 2. the nodes of the bad cells (those whose colour is in the gamut and shown exactly; nodes
//!    outside the gamut stay where the gamut mapping put them, and the greys `r = g = b`, black
//!    and white among them, stay exact: grey balance and white are judged on them alone) are
//!    moved, one at a time, by a
//!    damped Gauss–Newton step on the sum of squared CIELAB differences (relative to the
//!    display's white) over the samples they influence: the node itself and `2³ + 1` points
//!    inside each of its eight cells (at `1/4`, `3/4` and the centre), each weighted by the
//!    node's tetrahedral weight there being non-zero; samples whose colour is outside the gamut
//!    are not counted. A step is kept only when it lowers that sum;
//! 3. [`SWEEPS`] sweeps over those nodes, Gauss–Seidel by parity class: nodes whose `r`, `g`, `b`
//!    are even or odd alike share no cell, so each of the 8 classes is stepped at once (on the
//!    threads), seeing the nodes the classes before it moved.
//!
//! The nodes then no longer invert their own colours exactly (the node's own sample is one
//! term of its sum), in exchange for smaller errors between them.

use super::Target;
use specpoly_core::display_model::FULL;
use specpoly_core::{delta_e2000_xyz, DisplayModel, Lab};

/// ΔE00 at a cell's centre beyond which the cell's nodes are refined.
pub const CELL_DE: f64 = 0.2;
/// Gauss–Seidel sweeps.
pub const SWEEPS: usize = 3;
/// Positions of the samples inside a cell, per axis (and the centre).
const SUB: [f64; 2] = [0.25, 0.75];
/// Finite-difference step for the Jacobian (device units).
const STEP: f64 = 1e-4;

/// The tetrahedral weights of the cell's 8 corners (index `dr + 2 dg + 4 db`) at fractions `f`.
pub fn weights(f: [f64; 3]) -> [f64; 8] {
    let (fr, fg, fb) = (f[0], f[1], f[2]);
    let mut w = [0.0; 8];
    let mut put = |corner: usize, v: f64| w[corner] += v;
    // the six tetrahedra of Kasson et al. 1995 (as `Lut3d::apply`)
    if fr > fg {
        if fg > fb {
            put(0, 1.0 - fr);
            put(1, fr - fg);
            put(3, fg - fb);
            put(7, fb);
        } else if fr > fb {
            put(0, 1.0 - fr);
            put(1, fr - fb);
            put(5, fb - fg);
            put(7, fg);
        } else {
            put(0, 1.0 - fb);
            put(4, fb - fr);
            put(5, fr - fg);
            put(7, fg);
        }
    } else if fb > fg {
        put(0, 1.0 - fb);
        put(4, fb - fg);
        put(6, fg - fr);
        put(7, fr);
    } else if fb > fr {
        put(0, 1.0 - fg);
        put(2, fg - fb);
        put(6, fb - fr);
        put(7, fr);
    } else {
        put(0, 1.0 - fg);
        put(2, fg - fr);
        put(3, fr - fb);
        put(7, fb);
    }
    w
}

/// A sample: its source colour's CIELAB, its cell's base node and the corners' weights.
struct Sample {
    want: Lab,
    base: [usize; 3],
    w: [f64; 8],
}

/// The refinement's view of the LUT: the nodes as they stand, one of them possibly moved.
struct Grid<'a> {
    n: usize,
    nodes: &'a [[f64; 3]],
    model: &'a DisplayModel<FULL>,
    white: [f64; 3],
}

impl Grid<'_> {
    fn index(&self, r: usize, g: usize, b: usize) -> usize {
        r + self.n * (g + self.n * b)
    }

    fn corner(&self, base: [usize; 3], k: usize) -> usize {
        self.index(
            base[0] + (k & 1),
            base[1] + (k >> 1 & 1),
            base[2] + (k >> 2),
        )
    }

    /// CIELAB shown at a sample, node `moved.0` at `moved.1`.
    fn lab(&self, s: &Sample, moved: (usize, [f64; 3])) -> Lab {
        let mut d = [0.0; 3];
        for k in 0..8 {
            if s.w[k] != 0.0 {
                let i = self.corner(s.base, k);
                let v = if i == moved.0 { moved.1 } else { self.nodes[i] };
                for c in 0..3 {
                    d[c] += s.w[k] * v[c];
                }
            }
        }
        let xyz: [f64; 3] = self.model.device_to_xyz(d.map(|v| v as f32)).into();
        Lab::from_xyz(xyz, self.white)
    }

    /// One damped Gauss–Newton step for node `i` over its samples: its new value (the old one
    /// when no step lowers the sum).
    fn step(&self, i: usize, ss: &[Sample]) -> [f64; 3] {
        let v0 = self.nodes[i];
        let cost = |v: [f64; 3]| -> f64 {
            ss.iter()
                .map(|s| norm2(diff(self.lab(s, (i, v)), s.want)))
                .sum()
        };
        let cost0 = cost(v0);
        // normal equations, the Jacobian by forward differences
        let mut a = [[0.0f64; 3]; 3];
        let mut g = [0.0f64; 3];
        for s in ss {
            let r = diff(self.lab(s, (i, v0)), s.want);
            let mut j = [[0.0f64; 3]; 3];
            for c in 0..3 {
                let mut v = v0;
                v[c] += STEP;
                let rc = diff(self.lab(s, (i, v)), s.want);
                for row in 0..3 {
                    j[row][c] = (rc[row] - r[row]) / STEP;
                }
            }
            for p in 0..3 {
                for q in 0..3 {
                    a[p][q] += (0..3).map(|row| j[row][p] * j[row][q]).sum::<f64>();
                }
                g[p] += (0..3).map(|row| j[row][p] * r[row]).sum::<f64>();
            }
        }
        let mut mu = 1e-3 * (a[0][0] + a[1][1] + a[2][2]).max(1e-12);
        for _ in 0..8 {
            let mut m = a;
            for p in 0..3 {
                m[p][p] += mu;
            }
            if let Ok(inv) = specpoly_core::Mat3(m).inverse() {
                let step = inv.apply(g);
                let v = [0, 1, 2].map(|c| (v0[c] - step[c]).clamp(0.0, 1.0));
                if cost(v) < cost0 {
                    return v;
                }
            }
            mu *= 10.0;
        }
        v0
    }
}

fn diff(a: Lab, b: Lab) -> [f64; 3] {
    [a.l - b.l, a.a - b.a, a.b - b.b]
}

fn norm2(v: [f64; 3]) -> f64 {
    v[0] * v[0] + v[1] * v[1] + v[2] * v[2]
}

/// Refines `nodes` (red fastest, side `n`) in place (module docs); `shown[i]` says whether node
/// `i`'s colour is in the gamut and shown. Returns how many nodes were refined.
pub fn refine(
    model: &DisplayModel<FULL>,
    target: &Target,
    n: usize,
    nodes: &mut [[f64; 3]],
    shown: &[bool],
) -> usize {
    let top = (n - 1) as f64;
    let white = target.white();
    let cells = n - 1;
    let grid = Grid {
        n,
        nodes: &*nodes,
        model,
        white,
    };
    let centre_w = weights([0.5; 3]);
    // 1. bad cells
    let mut refine = vec![false; n * n * n];
    for cb in 0..cells {
        for cg in 0..cells {
            for cr in 0..cells {
                let base = [cr, cg, cb];
                let corners: Vec<usize> = (0..8).map(|k| grid.corner(base, k)).collect();
                if !corners.iter().any(|&i| shown[i]) {
                    continue;
                }
                let c = base.map(|j| (j as f64 + 0.5) / top);
                let want = target.xyz(c);
                if !target.in_gamut(want) {
                    continue;
                }
                let mut d = [0.0; 3];
                for (k, &i) in corners.iter().enumerate() {
                    for ch in 0..3 {
                        d[ch] += centre_w[k] * grid.nodes[i][ch];
                    }
                }
                let got: [f64; 3] = model.device_to_xyz(d.map(|v| v as f32)).into();
                if delta_e2000_xyz(got, want, white) > CELL_DE {
                    for &i in &corners {
                        refine[i] |= shown[i];
                    }
                }
            }
        }
    }
    // the greys (black and white among them) stay exact: verification judges them alone
    let grey = |i: usize| i % n == (i / n) % n && i % n == i / (n * n);
    let todo: Vec<usize> = (0..n * n * n).filter(|&i| refine[i] && !grey(i)).collect();
    // the samples each refined node influences
    let samples_of = |i: usize| -> Vec<Sample> {
        let p = [i % n, (i / n) % n, i / (n * n)];
        let mut out = Vec::new();
        let mut add = |base: [usize; 3], f: [f64; 3]| {
            let c = [0, 1, 2].map(|a| (base[a] as f64 + f[a]) / top);
            let want = target.xyz(c);
            if !target.in_gamut(want) {
                return;
            }
            let w = weights(f);
            // the node's corner in this cell
            let k = (p[0] - base[0]) + 2 * (p[1] - base[1]) + 4 * (p[2] - base[2]);
            if w[k] > 0.0 {
                out.push(Sample {
                    want: Lab::from_xyz(want, white),
                    base,
                    w,
                });
            }
        };
        // the node itself, in a cell it is the base of (or the last cell)
        let own = p.map(|v| v.min(cells - 1));
        add(own, [0, 1, 2].map(|a| (p[a] - own[a]) as f64));
        for db in 0..2 {
            for dg in 0..2 {
                for dr in 0..2 {
                    let d = [dr, dg, db];
                    if (0..3).any(|a| p[a] < d[a] || p[a] - d[a] >= cells) {
                        continue;
                    }
                    let base = [0, 1, 2].map(|a| p[a] - d[a]);
                    for &x in &SUB {
                        for &y in &SUB {
                            for &z in &SUB {
                                add(base, [x, y, z]);
                            }
                        }
                    }
                    add(base, [0.5; 3]);
                }
            }
        }
        out
    };
    let samples: Vec<Vec<Sample>> = todo.iter().map(|&i| samples_of(i)).collect();
    // nodes of one parity class (r, g, b mod 2) share no cell: each class is stepped at once,
    // on the threads, from the nodes as the previous classes left them (Gauss–Seidel by class)
    let threads = std::thread::available_parallelism()
        .map_or(1, |t| t.get())
        .clamp(1, 8);
    let class = |i: usize| (i % n % 2) + 2 * (i / n % n % 2) + 4 * (i / (n * n) % 2);
    for _ in 0..SWEEPS {
        for k in 0..8 {
            let members: Vec<(usize, &Vec<Sample>)> = todo
                .iter()
                .zip(&samples)
                .filter(|(i, ss)| class(**i) == k && !ss.is_empty())
                .map(|(i, ss)| (*i, ss))
                .collect();
            let view = Grid {
                n,
                nodes,
                model,
                white,
            };
            let chunk = members.len().div_ceil(threads).max(1);
            let moved: Vec<(usize, [f64; 3])> = std::thread::scope(|s| {
                let handles: Vec<_> = members
                    .chunks(chunk)
                    .map(|part| {
                        let view = &view;
                        s.spawn(move || {
                            part.iter()
                                .map(|(i, ss)| (*i, view.step(*i, ss)))
                                .collect::<Vec<_>>()
                        })
                    })
                    .collect();
                handles
                    .into_iter()
                    .flat_map(|h| h.join().unwrap_or_default())
                    .collect()
            });
            for (i, v) in moved {
                nodes[i] = v;
            }
        }
    }
    todo.len()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn tetrahedral_weights_sum_to_one_and_hit_the_corners() {
        for f in [
            [0.1, 0.5, 0.9],
            [0.9, 0.5, 0.1],
            [0.3, 0.3, 0.7],
            [0.0; 3],
            [1.0; 3],
        ] {
            let w = weights(f);
            assert!((w.iter().sum::<f64>() - 1.0).abs() < 1e-12);
            assert!(w.iter().all(|v| *v >= -1e-12));
            // they reproduce the position (affine precision)
            for a in 0..3 {
                let x: f64 = (0..8).map(|k| w[k] * ((k >> a) & 1) as f64).sum();
                assert!((x - f[a]).abs() < 1e-12);
            }
        }
        assert_eq!(weights([1.0; 3])[7], 1.0);
    }
}
