//! A display's full model: Cowan's matrix model ([`Display`]) plus an optional channel-
//! interaction lattice ([`Interaction`]),
//!
//! `f(rgb) = M · (t_R(r), t_G(g), t_B(b)) + black + L(rgb)`,
//!
//! with its forward evaluation, its exact inverse and its drive step. Every consumer of a
//! fitted calibration (`render --display`, `xyz --display`, `led --calibration`, the host's
//! `Calibration::predict`) evaluates and inverts the model here: one implementation.
//!
//! ## The inverse
//!
//! `f` has no closed-form inverse once `L` is present, and a table curve may be flat at its
//! foot (a panel that shows nothing below some level), where Newton's method stalls. For a
//! wanted XYZ `w`, [`DisplayModel::inverse`] minimises `‖(f(rgb) − w) / Y_white‖²` over the
//! cube `[0, 1]³`:
//!
//! 1. Start from the matrix model's inverse corrected for the lattice by fixed-point rounds,
//!    `rgb ← t⁻¹(clamp(M⁻¹(w − black − L(rgb))))` ([`FIXED_POINT_ROUNDS`]); keep the best.
//! 2. Levenberg–Marquardt steps with the analytic Jacobian `M · diag(t′(rgb)) + ∂L/∂rgb`,
//!    each step projected onto the cube and kept only when it lowers the cost (a channel at a
//!    face that the step would push out is held there and the step solved for the others;
//!    the damping grows until the cost falls; the small 3 × 3 systems are solved in f64 by [`crate::solve`]).
//!    When no step lowers it, one more try with a flat curve's slope replaced by its secant to
//!    where it rises ([`Transfer::rise`]): the way off a flat foot that the true slope, 0,
//!    cannot show; then once with central secants over 1/64 (slopes averaged across the kinks
//!    of the table curves and of the lattice's cells).
//! 3. If the prediction is still more than [`INVERSE_DE`] (ΔE00) off (a local minimum: where a
//!    curve is nearly flat, a lattice slope of the other sign makes the prediction fold back;
//!    or a stall on a kink of a table or the lattice), a branch and bound over the lattice's
//!    cells: a box is dropped when an enclosure of `f` over it excludes `w` (the matrix part
//!    from each channel's ends, since every curve is non-decreasing; the lattice from the
//!    box's corners, since it is trilinear inside a cell), otherwise halved on every channel
//!    (the halves whose centres come nearest first) down to [`LEAF`] a side, and step 2 runs
//!    from the centre of each box that is left, until one is exact. Every root lies in a box
//!    that is never dropped, so the descent starts within `LEAF / 2` of it (bounded by
//!    [`MAX_BOXES`] boxes and [`MAX_LEAF_STARTS`] descents).
//! 4. If still above (outside the gamut, or out of budget), each
//!    channel is scanned over its range (`SCAN_STEPS + 1` values, dense near 0, away from the
//!    current value); at each value the other two are refitted by the matrix model and then
//!    descended (step 2 with the channel held), and step 2 restarts from each channel's best
//!    point: at most [`SCAN_ROUNDS`] rounds.
//! 5. If still above: a coarse search over a `SEARCH_GRID³` lattice of device values (dense
//!    near 0 as the scans), and
//!    step 2 from the [`RESTARTS`] best of them.
//!
//! [`DisplayModel::inverse_with`] adds a step 0 — a descent from given device values (a
//! neighbouring colour's solution: continuation, which keeps neighbours on one branch where
//! the model folds), taken when it is exact — and can leave out steps 3–5, for colours already
//! mapped onto the gamut's boundary (3D LUTs, `specpoly_display::lut3d`).
//!
//! Inside the gamut (`w = f(rgb₀)` for some `rgb₀` in the cube) it returns device values whose
//! prediction is within [`INVERSE_DE`] of `w` (tested on every shipped display: ΔE00 ≤ 0.001
//! against an f64 evaluation of the model). Outside the gamut it returns the nearest
//! prediction the cube allows, in the least-squares sense above, flagged not exact.
//!
//! ## Gamut mapping
//!
//! [`DisplayModel::encode`] maps a colour with the matrix model's [`GamutMap`] (its gamut is
//! the matrix model's), then solves the full model for the matrix model's emission of the
//! mapped colour: the full model shows what the matrix model maps the colour to, exactly where
//! the two gamuts agree, and the nearest it can (flagged out of gamut) where they differ.

use crate::display::Encoded;
use crate::drive::{self, Drive};
use crate::interaction::{nodes, Interaction, GRID_MAX};
use crate::{delta_e2000, Display, GamutMap, Lab, Transfer, Xyz};

/// Nodes of the largest lattice a calibration file holds: the host's capacity.
pub const FULL: usize = nodes(GRID_MAX);

/// The CIEDE2000 difference (CIELAB relative to the model's white) between the prediction and
/// the wanted colour at or below which the inverse is exact: half the round-trip tolerance the
/// tests hold it to (0.001), so that f32 evaluation stays inside.
pub const INVERSE_DE: f64 = 0.0005;

/// Fixed-point rounds of the start (step 1).
pub const FIXED_POINT_ROUNDS: usize = 4;

/// Rounds of channel scans (step 4).
pub const SCAN_ROUNDS: usize = 5;

/// Values a channel scan tries: `(i / SCAN_STEPS)²`, `i = 0 ..= SCAN_STEPS`, dense near 0
/// where curves are flat.
pub const SCAN_STEPS: usize = 24;

/// Side of the coarse search lattice (step 5), at device values `(i / (SEARCH_GRID − 1))²`.
pub const SEARCH_GRID: usize = 7;

/// Starts taken from the coarse search (step 5).
pub const RESTARTS: usize = 3;

/// Side below which the cell search (step 3) stops bisecting a box and descends from its
/// centre: a table step of the finest curve.
pub const LEAF: f32 = 1.0 / 64.0;

/// Boxes the cell search may test per colour (its cost's bound).
pub const MAX_BOXES: u32 = 4096;

/// Descents the cell search may start per colour.
pub const MAX_LEAF_STARTS: u32 = 64;

/// How far outside its enclosure (over the white's `Y`) a box is still searched: the f32
/// evaluation's error, with room.
const ENCLOSURE_SLACK: f32 = 1e-5;

/// Levenberg–Marquardt iterations per start.
const MAX_ITERATIONS: u32 = 60;

/// The step of the secant Jacobian: a table step of the finest curve.
const SECANT_STEP: f32 = 1.0 / 64.0;

/// Stop when the residual is this small (the f32 evaluation's floor).
const FLOOR: f32 = 2e-8;

/// A display's full model with at most `CAP` interaction nodes.
#[derive(Clone, Debug, PartialEq)]
pub struct DisplayModel<const CAP: usize> {
    display: Display,
    interaction: Option<Interaction<CAP>>,
}

/// What [`DisplayModel::inverse`] found.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Solution {
    /// Device values in `[0, 1]³`.
    pub device: [f32; 3],
    /// The largest component of `|f(device) − w|`, over the white's `Y`.
    pub residual: f32,
    /// ΔE00 between the prediction at [`Self::device`] and the wanted colour (CIELAB relative
    /// to the model's white).
    pub delta_e00: f64,
    /// Whether [`Self::delta_e00`] is within [`INVERSE_DE`].
    pub exact: bool,
    /// Levenberg–Marquardt iterations taken, over all starts.
    pub iterations: u32,
    /// Starts tried (the first, one per box the cell search descends from, one per scan
    /// round, and those of the coarse search).
    pub starts: u32,
}

/// How [`DisplayModel::inverse_with`] searches; the default is [`DisplayModel::inverse`]'s.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct InverseOptions {
    /// Device values to descend from first (a neighbouring colour's solution).
    pub start: Option<[f32; 3]>,
    /// Whether the global steps 3–5 run when steps 1–2 miss.
    pub global: bool,
}

impl Default for InverseOptions {
    fn default() -> Self {
        Self {
            start: None,
            global: true,
        }
    }
}

/// The cell search's state (step 3): the wanted colour, the residuals' scale, what is left
/// of its budgets, and the iterations it took.
struct Search {
    w: [f32; 3],
    k: f32,
    boxes: u32,
    leaves: u32,
    iterations: u32,
}

/// `a + b`, component-wise.
fn add(a: [f32; 3], b: [f32; 3]) -> [f32; 3] {
    [a[0] + b[0], a[1] + b[1], a[2] + b[2]]
}

fn norm2(r: [f32; 3]) -> f32 {
    r[0] * r[0] + r[1] * r[1] + r[2] * r[2]
}

fn max_abs(r: [f32; 3]) -> f32 {
    r[0].abs().max(r[1].abs()).max(r[2].abs())
}

impl<const CAP: usize> DisplayModel<CAP> {
    /// The model of `display` with the lattice `interaction` (`None`: the matrix model).
    pub fn new(display: Display, interaction: Option<Interaction<CAP>>) -> Self {
        Self {
            display,
            interaction,
        }
    }

    /// The matrix model.
    pub fn display(&self) -> &Display {
        &self.display
    }

    /// The interaction lattice, if any.
    pub fn interaction(&self) -> Option<&Interaction<CAP>> {
        self.interaction.as_ref()
    }

    /// Predicted XYZ for device values `rgb ∈ [0, 1]³` (the display's units).
    pub fn device_to_xyz(&self, rgb: [f32; 3]) -> Xyz {
        let base = self.display.device_to_xyz(rgb);
        match &self.interaction {
            Some(l) => base + Xyz::from_array(l.eval(rgb)),
            None => base,
        }
    }

    /// XYZ at full drive of all three channels.
    pub fn white(&self) -> Xyz {
        self.device_to_xyz([1.0; 3])
    }

    /// The prediction at `rgb` and its Jacobian `j[row][channel]` (XYZ per device unit);
    /// with `rise`, a flat curve's slope is its secant to where it rises ([`Transfer::rise`]).
    fn with_jacobian(&self, rgb: [f32; 3], rise: bool) -> ([f32; 3], [[f32; 3]; 3]) {
        let m = &self.display.rgb_to_xyz().0;
        let t: &[Transfer; 3] = self.display.transfer();
        let slope = [0, 1, 2].map(|c| {
            if rise {
                t[c].rise(rgb[c])
            } else {
                t[c].slope(rgb[c])
            }
        });
        let mut j = [0, 1, 2].map(|r| [0, 1, 2].map(|c| m[r][c] * slope[c]));
        let mut f = self.display.device_to_xyz(rgb).to_array();
        if let Some(l) = &self.interaction {
            let (v, s) = l.eval_with_slope(rgb);
            f = add(f, v);
            for r in 0..3 {
                for c in 0..3 {
                    j[r][c] += s[c][r];
                }
            }
        }
        (f, j)
    }

    /// The Jacobian by central secants over [`SECANT_STEP`] (one-sided at the cube's faces):
    /// slopes averaged across the kinks of the table curves and the lattice's cells.
    fn secant_jacobian(&self, rgb: [f32; 3]) -> [[f32; 3]; 3] {
        let mut j = [[0.0f32; 3]; 3];
        for c in 0..3 {
            let (mut lo, mut hi) = (rgb, rgb);
            lo[c] = (rgb[c] - SECANT_STEP).max(0.0);
            hi[c] = (rgb[c] + SECANT_STEP).min(1.0);
            let (a, b) = (self.device_to_xyz(lo), self.device_to_xyz(hi));
            let h = hi[c] - lo[c];
            let d = [b.x - a.x, b.y - a.y, b.z - a.z];
            for r in 0..3 {
                j[r][c] = d[r] / h;
            }
        }
        j
    }

    /// `1 / Y_white`, the residuals' scale.
    fn inv_scale(&self) -> f32 {
        let y = self.display.white().y.abs();
        if y > f32::MIN_POSITIVE {
            1.0 / y
        } else {
            1.0
        }
    }

    /// Device values whose prediction is `xyz` (display units): see the module docs.
    pub fn inverse(&self, xyz: Xyz) -> Solution {
        self.inverse_with(xyz, InverseOptions::default())
    }

    /// [`Self::inverse`] with a start and without the global steps, as `opts` says.
    ///
    /// - `start`: Levenberg–Marquardt (step 2) first descends from these device values (a
    ///   neighbour's solution: continuation); when that reaches the colour it is the answer,
    ///   else the steps below run as usual and the better of the two is kept. Where the model
    ///   folds (two device colours show one colour), neighbouring colours so stay on one branch.
    /// - `global: false`: steps 1 and 2 only — for a colour mapped onto the gamut's boundary
    ///   or known to lie outside it, where steps 3–5 would only search for a root that is not
    ///   there; [`Solution::exact`] says whether it was reached.
    pub fn inverse_with(&self, xyz: Xyz, opts: InverseOptions) -> Solution {
        let w = xyz.to_array();
        let k = self.inv_scale();
        let resid = |x: [f32; 3]| {
            let p = self.device_to_xyz(x).to_array();
            [0, 1, 2].map(|r| (p[r] - w[r]) * k)
        };
        let white = self.white();
        let lab_w = Lab::from_xyz(xyz, white);
        let miss = |x: [f32; 3]| delta_e2000(Lab::from_xyz(self.device_to_xyz(x), white), lab_w);
        let global = opts.global;
        // 0. from the given start
        let mut from_start = None;
        if let Some(s) = opts.start {
            let s = s.map(|v| {
                if v.is_finite() {
                    v.clamp(0.0, 1.0)
                } else {
                    0.5
                }
            });
            let (x, cost, n) = self.descend(&resid, k, s, [false; 3]);
            let delta_e00 = miss(x);
            let sol = Solution {
                device: x,
                residual: max_abs(resid(x)),
                delta_e00,
                exact: delta_e00 <= INVERSE_DE,
                iterations: n,
                starts: 1,
            };
            if sol.exact {
                return sol;
            }
            from_start = Some((sol, cost));
        }
        // 1. the matrix model's inverse, corrected for the lattice (`xyz_to_linear` takes the
        // black off)
        let t = self.display.transfer();
        let mut x = [0.0f32; 3];
        let mut best = ([0.0f32; 3], f32::INFINITY);
        for _ in 0..FIXED_POINT_ROUNDS {
            let l = self.interaction.as_ref().map_or([0.0; 3], |l| l.eval(x));
            let v = [0, 1, 2].map(|r| w[r] - l[r]);
            let lin = self.display.xyz_to_linear(Xyz::from_array(v));
            x = [0, 1, 2].map(|c| {
                let d = t[c].encode(lin[c]);
                if d.is_finite() {
                    d
                } else {
                    0.5
                }
            });
            let c = norm2(resid(x));
            if c < best.1 {
                best = (x, c);
            }
            if self.interaction.is_none() {
                break;
            }
        }
        // 2. Levenberg–Marquardt from there
        let (mut x, mut cost, mut iterations) = self.descend(&resid, k, best.0, [false; 3]);
        let mut starts = 1;
        // 3. the lattice cells that may hold a root, bisected, a descent from each small box
        // that still may
        if let Some(l) = self
            .interaction
            .as_ref()
            .filter(|_| global && miss(x) > INVERSE_DE)
        {
            let mut s = Search {
                w,
                k,
                boxes: MAX_BOXES,
                leaves: MAX_LEAF_STARTS,
                iterations: 0,
            };
            let exact = |y: [f32; 3]| miss(y) <= INVERSE_DE;
            let found = self.cell_search(l, &resid, &exact, &mut s);
            iterations += s.iterations;
            starts += MAX_LEAF_STARTS - s.leaves;
            if let Some((y, cy)) = found {
                (x, cost) = (y, cy);
            }
        }
        // 4. channel scans: each channel over its whole range, the other two refitted by the
        // matrix model at each value; a descent from the best point found
        for _ in 0..SCAN_ROUNDS {
            if !global || miss(x) <= INVERSE_DE {
                break;
            }
            let mut improved = false;
            let from = x;
            for c in 0..3 {
                // the best value of channel c, the others refitted, away from where we stand
                let mut p = (from, f32::INFINITY);
                for i in 0..=SCAN_STEPS {
                    let f = i as f32 / SCAN_STEPS as f32;
                    if (f * f - from[c]).abs() < 0.5 / SCAN_STEPS as f32 {
                        continue;
                    }
                    let mut q = from;
                    q[c] = f * f;
                    let q = self.refit_others(q, c, w);
                    // the profile: the other two descended with channel c held
                    let mut hold = [false; 3];
                    hold[c] = true;
                    let (q, cq, n) = self.descend(&resid, k, q, hold);
                    iterations += n;
                    if cq < p.1 {
                        p = (q, cq);
                    }
                }
                if !p.1.is_finite() {
                    continue;
                }
                let (y, cy, n) = self.descend(&resid, k, p.0, [false; 3]);
                iterations += n;
                starts += 1;
                if cy < cost {
                    (x, cost) = (y, cy);
                    improved = true;
                }
            }
            if !improved {
                break;
            }
        }
        // 5. a coarse search, and descents from its best points
        if global && miss(x) > INVERSE_DE {
            let mut seeds = [([0.0f32; 3], f32::INFINITY); RESTARTS];
            let top = (SEARCH_GRID - 1) as f32;
            for i in 0..nodes(SEARCH_GRID) {
                let p = [
                    i / (SEARCH_GRID * SEARCH_GRID),
                    i / SEARCH_GRID % SEARCH_GRID,
                    i % SEARCH_GRID,
                ]
                .map(|n| {
                    let f = n as f32 / top;
                    f * f
                });
                let c = norm2(resid(p));
                // keep the RESTARTS lowest, sorted
                if c < seeds[RESTARTS - 1].1 {
                    let mut at = RESTARTS - 1;
                    while at > 0 && seeds[at - 1].1 > c {
                        seeds[at] = seeds[at - 1];
                        at -= 1;
                    }
                    seeds[at] = (p, c);
                }
            }
            for (p, c) in seeds {
                if !c.is_finite() {
                    continue;
                }
                let (y, cy, n) = self.descend(&resid, k, p, [false; 3]);
                iterations += n;
                starts += 1;
                if cy < cost {
                    (x, cost) = (y, cy);
                }
                if miss(x) <= INVERSE_DE {
                    break;
                }
            }
        }
        if let Some((sol, c)) = from_start {
            iterations += sol.iterations;
            starts += 1;
            if c < cost {
                x = sol.device;
            }
        }
        let delta_e00 = miss(x);
        Solution {
            device: x,
            residual: max_abs(resid(x)),
            delta_e00,
            exact: delta_e00 <= INVERSE_DE,
            iterations,
            starts,
        }
    }

    /// Step 3: every lattice cell that [`Self::may_hold`] a root, bisected
    /// ([`Self::bisect`]); the first exact point found and its cost.
    fn cell_search(
        &self,
        l: &Interaction<CAP>,
        resid: &impl Fn([f32; 3]) -> [f32; 3],
        exact: &impl Fn([f32; 3]) -> bool,
        s: &mut Search,
    ) -> Option<([f32; 3], f32)> {
        let g = l.grid();
        let top = (g - 1) as f32;
        let cells = g - 1;
        (0..cells * cells * cells).find_map(|i| {
            let j = [i / (cells * cells), i / cells % cells, i % cells];
            let (lo, hi) = (j.map(|n| n as f32 / top), j.map(|n| (n + 1) as f32 / top));
            self.bisect(l, lo, hi, resid, exact, s)
        })
    }

    /// The box `[lo, hi]` (inside one lattice cell): nothing if it cannot hold a root; a
    /// descent from its centre if it is at most [`LEAF`] a side; else its eight halves, those
    /// whose centres come nearest first. The first exact point found and its cost.
    fn bisect(
        &self,
        l: &Interaction<CAP>,
        lo: [f32; 3],
        hi: [f32; 3],
        resid: &impl Fn([f32; 3]) -> [f32; 3],
        exact: &impl Fn([f32; 3]) -> bool,
        s: &mut Search,
    ) -> Option<([f32; 3], f32)> {
        if s.boxes == 0 || s.leaves == 0 {
            return None;
        }
        s.boxes -= 1;
        if !self.may_hold(l, lo, hi, s) {
            return None;
        }
        let mid = [0, 1, 2].map(|c| 0.5 * (lo[c] + hi[c]));
        if (0..3).all(|c| hi[c] - lo[c] <= LEAF) {
            s.leaves -= 1;
            let (y, cy, n) = self.descend(resid, s.k, mid, [false; 3]);
            s.iterations += n;
            return exact(y).then_some((y, cy));
        }
        // half `i`: bit 2 − c says the upper half of channel c
        let half = |i: usize| -> ([f32; 3], [f32; 3]) {
            let (mut a, mut b) = (lo, mid);
            for c in 0..3 {
                if i >> (2 - c) & 1 == 1 {
                    (a[c], b[c]) = (mid[c], hi[c]);
                }
            }
            (a, b)
        };
        let mut order = [(0u8, 0.0f32); 8];
        for (i, o) in order.iter_mut().enumerate() {
            let (a, b) = half(i);
            *o = (
                i as u8,
                norm2(resid([0, 1, 2].map(|c| 0.5 * (a[c] + b[c])))),
            );
        }
        order.sort_unstable_by(|p, q| p.1.total_cmp(&q.1));
        order.iter().find_map(|&(i, _)| {
            let (a, b) = half(i as usize);
            self.bisect(l, a, b, resid, exact, s)
        })
    }

    /// Whether `f − s.w` may vanish on the box `[lo, hi]` inside one lattice cell: an enclosure
    /// of `f` there, the matrix part from each channel's ends (the curves never decrease), the
    /// lattice's from the box's corners (trilinear inside a cell, it takes its extremes
    /// there), each component widened by [`ENCLOSURE_SLACK`] of the white's `Y`.
    fn may_hold(&self, l: &Interaction<CAP>, lo: [f32; 3], hi: [f32; 3], s: &Search) -> bool {
        let (w, k) = (s.w, s.k);
        let m = &self.display.rgb_to_xyz().0;
        let t = self.display.transfer();
        let b = self.display.black().to_array();
        let tl = [0, 1, 2].map(|c| t[c].decode(lo[c]));
        let th = [0, 1, 2].map(|c| t[c].decode(hi[c]));
        let mut low = [0, 1, 2].map(|r| b[r] - w[r]);
        let mut high = low;
        for r in 0..3 {
            for c in 0..3 {
                let (p, q) = (m[r][c] * tl[c], m[r][c] * th[c]);
                low[r] += p.min(q);
                high[r] += p.max(q);
            }
        }
        let (mut lmin, mut lmax) = ([f32::INFINITY; 3], [f32::NEG_INFINITY; 3]);
        for corner in 0..8 {
            let p = [0, 1, 2].map(|c| {
                if corner >> (2 - c) & 1 == 1 {
                    hi[c]
                } else {
                    lo[c]
                }
            });
            let v = l.eval(p);
            for r in 0..3 {
                lmin[r] = lmin[r].min(v[r]);
                lmax[r] = lmax[r].max(v[r]);
            }
        }
        (0..3).all(|r| {
            (low[r] + lmin[r]) * k <= ENCLOSURE_SLACK && (high[r] + lmax[r]) * k >= -ENCLOSURE_SLACK
        })
    }

    /// `q` with the two channels other than `c` set so that the matrix model, with the lattice
    /// at `q`, comes nearest `w` in least squares (two rounds, the lattice re-read at the new
    /// point): how a scan of channel `c` keeps the others in step.
    fn refit_others(&self, mut q: [f32; 3], c: usize, w: [f32; 3]) -> [f32; 3] {
        let m = &self.display.rgb_to_xyz().0;
        let t = self.display.transfer();
        let b = self.display.black().to_array();
        let (o1, o2) = ((c + 1) % 3, (c + 2) % 3);
        for _ in 0..2 {
            let l = self.interaction.as_ref().map_or([0.0; 3], |l| l.eval(q));
            let tc = t[c].decode(q[c]);
            let rhs = [0, 1, 2].map(|r| (w[r] - b[r] - l[r] - m[r][c] * tc) as f64);
            let col = |o: usize| [0, 1, 2].map(|r| m[r][o] as f64);
            let (p1, p2) = (col(o1), col(o2));
            let dot = |a: [f64; 3], b: [f64; 3]| a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
            let (a11, a12, a22) = (dot(p1, p1), dot(p1, p2), dot(p2, p2));
            let (r1, r2) = (dot(p1, rhs), dot(p2, rhs));
            let det = a11 * a22 - a12 * a12;
            if !(det.abs() > 1e-12 * a11 * a22) {
                return q;
            }
            let u1 = (r1 * a22 - r2 * a12) / det;
            let u2 = (a11 * r2 - a12 * r1) / det;
            q[o1] = t[o1].encode(u1 as f32);
            q[o2] = t[o2].encode(u2 as f32);
        }
        q
    }

    /// Levenberg–Marquardt descent of `‖resid‖²` from `x` inside the cube (step 2), the
    /// channels of `hold` held where they are: the point, its cost and the iterations taken.
    fn descend(
        &self,
        resid: &impl Fn([f32; 3]) -> [f32; 3],
        k: f32,
        mut x: [f32; 3],
        hold: [bool; 3],
    ) -> ([f32; 3], f32, u32) {
        let mut r = resid(x);
        let mut cost = norm2(r);
        let mut mu = 1e-3f64;
        let mut n = 0;
        // exact slopes; after a stall, once with flat curves' secants (to leave a flat foot)
        // 0: exact slopes; 1: flat curves' secants; 2: secants over SECANT_STEP
        let mut mode = 0;
        while n < MAX_ITERATIONS && max_abs(r) > FLOOR {
            n += 1;
            let j = if mode < 2 {
                self.with_jacobian(x, mode == 1).1
            } else {
                self.secant_jacobian(x)
            };
            let j = j.map(|row| row.map(|v| (v * k) as f64));
            // normal equations JᵀJ δ = −Jᵀr, damped on the diagonal
            let mut a = [[0.0f64; 3]; 3];
            let mut g = [0.0f64; 3];
            for p in 0..3 {
                for q in 0..3 {
                    a[p][q] = (0..3).map(|row| j[row][p] * j[row][q]).sum();
                }
                g[p] = -(0..3).map(|row| j[row][p] * r[row] as f64).sum::<f64>();
            }
            let trace = a[0][0] + a[1][1] + a[2][2];
            let mut accepted = false;
            for _ in 0..16 {
                // channels held at a face of the cube that the step would push out of are
                // fixed there and the step solved for the others (an active set)
                let mut held = hold;
                let mut step = [0.0f64; 3];
                let mut solved = false;
                for _ in 0..3 {
                    let mut m = a;
                    step = g;
                    for p in 0..3 {
                        m[p][p] += mu * a[p][p] + 1e-12 * trace + 1e-30;
                        if held[p] {
                            for q in 0..3 {
                                m[p][q] = if p == q { 1.0 } else { 0.0 };
                                m[q][p] = if p == q { 1.0 } else { 0.0 };
                            }
                            step[p] = 0.0;
                        }
                    }
                    solved = crate::solve::solve(m.as_flattened_mut(), &mut step).is_ok();
                    if !solved {
                        break;
                    }
                    let mut more = false;
                    for c in 0..3 {
                        let out = (x[c] <= 0.0 && step[c] < 0.0) || (x[c] >= 1.0 && step[c] > 0.0);
                        if out && !held[c] {
                            held[c] = true;
                            more = true;
                        }
                    }
                    if !more {
                        break;
                    }
                }
                if !solved {
                    mu *= 10.0;
                    continue;
                }
                let xn = [0, 1, 2].map(|c| (x[c] + step[c] as f32).clamp(0.0, 1.0));
                let rn = resid(xn);
                let cn = norm2(rn);
                if cn < cost {
                    accepted = xn != x;
                    (x, r, cost) = (xn, rn, cn);
                    mu = (mu / 3.0).max(1e-9);
                    break;
                }
                mu *= 4.0;
            }
            if accepted {
                mode = 0;
            } else if mode == 2 {
                break;
            } else {
                mode += 1;
            }
        }
        (x, cost, n)
    }

    /// Encodes an absolute XYZ (display units) into device values: the matrix model's gamut
    /// mapping, then the full model's inverse of the matrix model's emission (module docs).
    /// `linear` is each channel's linear light at the device values found.
    pub fn encode(&self, xyz: Xyz, map: GamutMap) -> Encoded {
        let e = self.display.encode(xyz, map);
        if self.interaction.is_none() {
            return e;
        }
        let target =
            Xyz::from_array(self.display.rgb_to_xyz().apply(e.linear)) + self.display.black();
        let s = self.inverse(target);
        let t = self.display.transfer();
        Encoded {
            device: s.device,
            linear: [0, 1, 2].map(|c| t[c].decode(s.device[c])),
            out_of_gamut: e.out_of_gamut || !s.exact,
        }
    }

    /// Encodes a colour relative to a white of `Y = 100` ([`Display::encode_relative`]'s
    /// scale: the matrix model's).
    pub fn encode_relative(&self, xyz: Xyz, map: GamutMap) -> Encoded {
        let d = &self.display;
        let k = (d.white().y - d.black().y) / 100.0;
        self.encode(xyz.scale(k), map)
    }

    /// The drive step for `target` (white `Y = 100`) on levels `0 ..= max`
    /// ([`Display::drive`] with the full model's encoding and emission).
    pub fn drive(&self, target: Xyz, map: GamutMap, max: u16) -> Drive {
        drive::step(
            self.encode_relative(target, map),
            max,
            self.display.white().y,
            |shown| self.device_to_xyz(shown),
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A display whose red curve is flat over its first eighth, with a lattice that makes the
    /// channels interact: every device colour comes back from its own prediction.
    #[test]
    fn inverts_a_flat_footed_interacting_display() {
        let mut red = [0.0f32; 33];
        for (i, v) in red.iter_mut().enumerate() {
            let d = i as f32 / 32.0;
            *v = if d <= 0.125 {
                0.0
            } else {
                ((d - 0.125) / 0.875).powf(2.2)
            };
        }
        let (xy, lum) = Display::srgb().primaries();
        let d = Display::from_primaries(
            xy,
            lum.map(|l| l * 100.0),
            Xyz::new(0.2, 0.21, 0.25),
            [
                Transfer::table(&red).unwrap(),
                Transfer::Gamma(2.4),
                Transfer::Srgb,
            ],
        )
        .unwrap();
        let g = 3;
        let vals = (0..nodes(g)).map(|i| {
            let p = [i / 9, i / 3 % 3, i % 3].map(|n| n as f32 / 2.0);
            [
                -0.3 * p[0] * p[1],
                -0.2 * p[1] * p[2] + 0.1 * p[0],
                -0.4 * p[0] * p[2],
            ]
        });
        let m = DisplayModel::new(d, Some(Interaction::<27>::new(g, vals).unwrap()));
        let levels = [0.0, 0.03, 0.1, 0.2, 0.5, 0.8, 1.0];
        for r in levels {
            for gg in levels {
                for b in levels {
                    let w = m.device_to_xyz([r, gg, b]);
                    let s = m.inverse(w);
                    assert!(s.exact, "({r}, {gg}, {b}): {s:?}");
                }
            }
        }
        // continuation: from a neighbour's solution on the flat foot's top, a darker red stays
        // there (the foot shows no light: every red in it is a solution)
        let w = m.device_to_xyz([0.125, 0.5, 0.5]);
        let s = m.inverse_with(
            w,
            InverseOptions {
                start: Some([0.13, 0.5, 0.5]),
                global: true,
            },
        );
        assert!(
            s.exact && s.starts == 1 && (s.device[0] - 0.125).abs() < 0.01,
            "{s:?}"
        );
        // without the global steps an unreachable colour costs one start
        let far = Xyz::new(0.0, 150.0, 0.0);
        let local = m.inverse_with(
            far,
            InverseOptions {
                start: None,
                global: false,
            },
        );
        assert!(!local.exact && local.starts == 1, "{local:?}");
        assert!(m.inverse(far).starts > 1);
    }

    /// Step 1 is the matrix model's exact inverse: with a black, a colour on the cube's face
    /// (a power-law channel at 0, whose slope there is 0) is reached without the global steps.
    #[test]
    fn the_start_is_the_matrix_inverse_with_a_black() {
        let (xy, lum) = Display::srgb().primaries();
        let d = Display::from_primaries(
            xy,
            lum.map(|l| l * 100.0),
            Xyz::new(0.1, 0.1, 0.12),
            [
                Transfer::Gamma(2.2),
                Transfer::Gamma(2.2),
                Transfer::Gamma(2.2),
            ],
        )
        .unwrap();
        let m = DisplayModel::<8>::new(d, None);
        for rgb in [[0.0912, 0.0, 0.0], [0.3, 0.0, 0.7], [0.0, 0.05, 0.0]] {
            let s = m.inverse_with(
                m.device_to_xyz(rgb),
                InverseOptions {
                    start: None,
                    global: false,
                },
            );
            assert!(s.exact && s.starts == 1, "{rgb:?}: {s:?}");
            assert!(
                (0..3).all(|c| (s.device[c] - rgb[c]).abs() < 1e-3),
                "{rgb:?}: {s:?}"
            );
        }
    }

    #[test]
    fn without_a_lattice_the_encoding_is_the_matrix_models() {
        let m = DisplayModel::<8>::new(Display::srgb(), None);
        let x = Xyz::new(30.0, 20.0, 10.0);
        assert_eq!(
            m.encode_relative(x, GamutMap::Clip),
            Display::srgb().encode_relative(x, GamutMap::Clip)
        );
        assert_eq!(
            m.drive(x, GamutMap::Clip, 255),
            Display::srgb().drive(x, GamutMap::Clip, 255)
        );
    }
}
