//! A drive-correction table: the full display model's exact inverse ([`DisplayModel::inverse`])
//! tabulated for a controller that evaluates only Cowan's matrix model ([`Display`]).
//!
//! A microcontroller cannot run the full model's inverse (Levenberg–Marquardt, scans, a coarse
//! search: see [`crate::display_model`]) nor hold its lattice in RAM. The host therefore
//! tabulates, on a regular `g × g × g` grid over the matrix model's device values
//! `d ∈ [0, 1]³` (nodes at `(i/(g−1))²` per axis: [`position`]), the correction
//!
//! `Δ(d) = inverse_full(f_m(d)) − d`,
//!
//! where `f_m(d) = M · t(d)` is the controller's matrix model (Cowan 1983, the paper's §7.3:
//! primaries and curves as the controller has them, black 0) and `inverse_full` is the full
//! model's exact inverse, so that the display driven at `d + Δ(d)` emits what the matrix model
//! promised for `d`: the channel interaction and the black flare are both corrected. Nodes are
//! stored red slowest, blue fastest (the layout of
//! [`crate::Interaction`]); each holds `Δ` in i16 fixed point, `Δ = v / ONE` (Q15, so
//! `−1 ≤ Δ < 1`: 3.1·10⁻⁵ a step, two steps of a 16-bit duty and 1/128 of an 8-bit one).
//!
//! The controller applies it after the matrix model's drive step ([`corrected`]): levels
//! `l` of `d = t⁻¹(clip(M⁻¹ xyz))`, then `d′ = clamp(l / max + trilinear Δ(l / max))`, levels
//! `round(d′ · max)`. The
//! nodes are read one at a time through [`Nodes`] (the firmware reads the eight corners of the
//! cell from flash; the host from a slice), so the table is never copied into RAM. The host's
//! model of the controller calls the same function: one implementation.
//!
//! [`checksum`] (FNV-1a, 32 bits; written here rather than taken from the `fnv` crate because
//! it is six lines over bytes that both sides already hold, and the protocol's documentation
//! can state it in one line for other hosts) guards the upload; [`calibration_key`] binds a table to
//! the calibration (primaries and curves) it was made for, so that a table is applied only
//! with that calibration.

use crate::drive::Drive;
use crate::{quantize, Display, DisplayModel, Transfer};
#[cfg(test)]
use crate::{GamutMap, Xyz};

/// Smallest grid side.
pub const GRID_MIN: usize = 2;

/// Largest grid side: 17³ nodes (29 KiB); what fits a controller is chosen by measured
/// accuracy (docs/calibration.md).
pub const GRID_MAX: usize = 17;

/// Fixed-point scale of the nodes: `Δ = v / ONE` (Q15).
pub const ONE: f32 = 32768.0;

/// A table's nodes, read one at a time.
pub trait Nodes {
    /// Nodes per side (`GRID_MIN ..= GRID_MAX`); below [`GRID_MIN`] there is no table.
    fn grid(&self) -> usize;
    /// Node `index` (`(i · g + j) · g + k`); a node that cannot be read is 0 (no correction).
    fn node(&mut self, index: usize) -> [i16; 3];
}

/// A table held in memory (the host's): `grid³` nodes, red slowest.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Table<'a> {
    grid: usize,
    nodes: &'a [[i16; 3]],
}

impl<'a> Table<'a> {
    /// The table of side `grid` over `nodes`; `None` unless `nodes` holds `grid³` nodes and
    /// `grid` is within [`GRID_MIN`]–[`GRID_MAX`].
    pub fn new(grid: usize, nodes: &'a [[i16; 3]]) -> Option<Self> {
        ((GRID_MIN..=GRID_MAX).contains(&grid) && nodes.len() == grid * grid * grid)
            .then_some(Self { grid, nodes })
    }
}

impl Nodes for Table<'_> {
    fn grid(&self) -> usize {
        self.grid
    }
    fn node(&mut self, index: usize) -> [i16; 3] {
        self.nodes.get(index).copied().unwrap_or([0; 3])
    }
}

/// The correction `Δ(d)` (device units) at the matrix model's device values `d` (clamped to
/// `[0, 1]³`; NaN reads as 0): trilinear in `√d` between the cell's eight corners (nodes at
/// [`position`]), read in turn.
pub fn correction(table: &mut (impl Nodes + ?Sized), d: [f32; 3]) -> [f32; 3] {
    let g = table.grid();
    if !(GRID_MIN..=GRID_MAX).contains(&g) {
        return [0.0; 3];
    }
    let top = (g - 1) as f32;
    let mut j = [0usize; 3];
    let mut f = [0.0f32; 3];
    for c in 0..3 {
        let v = if d[c].is_nan() {
            0.0
        } else {
            d[c].clamp(0.0, 1.0)
        };
        // nodes at (n / top)²: the cell of √d
        let x = libm::sqrtf(v) * top;
        j[c] = (x as usize).min(g - 2);
        f[c] = x - j[c] as f32;
    }
    let mut acc = [0.0f32; 3];
    for corner in 0..8usize {
        let s = [corner >> 2 & 1, corner >> 1 & 1, corner & 1];
        let w = [0, 1, 2].map(|c| if s[c] == 1 { f[c] } else { 1.0 - f[c] });
        let weight = w[0] * w[1] * w[2];
        let node = table.node(((j[0] + s[0]) * g + j[1] + s[1]) * g + j[2] + s[2]);
        for r in 0..3 {
            acc[r] += weight * node[r] as f32;
        }
    }
    acc.map(|v| v / ONE)
}

/// The drive step `plain` (the matrix model's, [`Display::drive`]) corrected by `table`: the
/// matrix model's levels `l` give `d = l / max`, and the levels become
/// `round(clamp(d + Δ(d)) · max)`. `linear`, `emitted` and `out_of_gamut` stay the matrix
/// model's: the full model at the new levels shows what the matrix model promised at the old
/// ones, to within the table's interpolation error and one level step. Correcting the
/// quantised levels (rather than the unquantised device values) keeps the controller's code
/// to this one function after the kernels' drive step: the input moves by at most half a
/// level, over which `Δ` changes by its slope times that.
pub fn corrected(table: &mut (impl Nodes + ?Sized), plain: Drive, max: u16) -> Drive {
    let full = max.max(1) as f32;
    let d = plain.level.map(|l| l as f32 / full);
    let delta = correction(table, d);
    Drive {
        level: [0, 1, 2].map(|c| quantize(d[c] + delta[c], max)),
        ..plain
    }
}

/// The device value of node `n` along an axis of `top + 1` nodes: `(n / top)²`, dense near
/// black, where the correction turns fastest (it takes the black flare off: `Δ = −d` at the
/// foot, then bends).
pub fn position(n: usize, top: f32) -> f32 {
    let u = n as f32 / top;
    u * u
}

/// Node `index` of the table of side `grid` that corrects `matrix` (the controller's matrix
/// model, in the units of `model`) toward `model`: `round(ONE · (inverse_full(f_m(d)) − d))`
/// at `d = (i, j, k) / (grid − 1)`, saturated to i16. Where `f_m(d)` is outside the full
/// model's gamut (below its black, beyond its white) the inverse's least-squares nearest.
pub fn node<const CAP: usize>(
    model: &DisplayModel<CAP>,
    matrix: &Display,
    grid: usize,
    index: usize,
) -> [i16; 3] {
    let g = grid.max(2);
    let top = (g - 1) as f32;
    let d = [index / (g * g), index / g % g, index % g].map(|n| position(n, top));
    let s = model.inverse(matrix.device_to_xyz(d));
    [0, 1, 2].map(|c| {
        let x = (s.device[c] - d[c]) * ONE;
        // round half away from 0 (no `round` in `core`), saturated to i16
        let v = if x >= 0.0 { x + 0.5 } else { x - 0.5 } as i32;
        v.clamp(i16::MIN as i32, i16::MAX as i32) as i16
    })
}

/// FNV-1a (32 bits) offset basis and prime.
const FNV_BASIS: u32 = 0x811c_9dc5;
const FNV_PRIME: u32 = 0x0100_0193;

/// Folds bytes into an FNV-1a hash.
fn fnv(mut h: u32, bytes: &[u8]) -> u32 {
    for b in bytes {
        h = (h ^ *b as u32).wrapping_mul(FNV_PRIME);
    }
    h
}

/// The upload's checksum: FNV-1a over the grid side (one byte) and every node's three values
/// (little-endian i16), in node order.
pub fn checksum(grid: usize, nodes: impl IntoIterator<Item = [i16; 3]>) -> u32 {
    let mut h = fnv(FNV_BASIS, &[grid as u8]);
    for n in nodes {
        for v in n {
            h = fnv(h, &v.to_le_bytes());
        }
    }
    h
}

/// A hash of the calibration a table corrects: the primaries' `x, y, Y` and the three curves
/// (kind, and a gamma's or table's values), as f32 bit patterns. A controller applies a table
/// only while its calibration has the key the table was stored with.
pub fn calibration_key(xy: [[f32; 2]; 3], luminance: [f32; 3], trc: &[Transfer; 3]) -> u32 {
    let mut h = FNV_BASIS;
    for i in 0..3 {
        for v in [xy[i][0], xy[i][1], luminance[i]] {
            h = fnv(h, &v.to_bits().to_le_bytes());
        }
    }
    for t in trc {
        match t {
            Transfer::Linear => h = fnv(h, &[0]),
            Transfer::Srgb => h = fnv(h, &[1]),
            Transfer::Gamma(g) => {
                h = fnv(h, &[2]);
                h = fnv(h, &g.to_bits().to_le_bytes());
            }
            Transfer::Table(v) => {
                h = fnv(h, &[3, v.len() as u8]);
                for x in v {
                    h = fnv(h, &x.to_bits().to_le_bytes());
                }
            }
        }
    }
    h
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::Interaction;

    /// A correction multilinear in `√d` is reproduced exactly between its nodes (trilinear
    /// interpolation in `√d` is exact on it), read corner by corner.
    #[test]
    fn interpolates_a_multilinear_correction() {
        let f = |d: [f32; 3]| {
            let u = d.map(libm::sqrtf);
            [0.1 * u[0] * u[1], -0.05 * u[2], 0.2 * u[0] * u[1] * u[2]]
        };
        for g in [2usize, 3, 5] {
            let top = (g - 1) as f32;
            let nodes: [[i16; 3]; 125] = core::array::from_fn(|i| {
                let d = [i / (g * g), i / g % g, i % g].map(|n| position(n, top));
                f(d).map(|v| (v * ONE).round() as i16)
            });
            let mut t = Table::new(g, &nodes[..g * g * g]).unwrap();
            let d = [0.31, 0.77, 0.52];
            let c = correction(&mut t, d);
            for r in 0..3 {
                assert!((c[r] - f(d)[r]).abs() < 2.0 / ONE, "g {g}: {c:?}");
            }
        }
        assert!(Table::new(3, &[[0; 3]; 26]).is_none());
        assert!(Table::new(1, &[[0; 3]; 1]).is_none());
    }

    /// With a zero table the corrected drive is the matrix model's.
    #[test]
    fn a_zero_table_changes_nothing() {
        let d = Display::srgb();
        let zeros = [[0i16; 3]; 8];
        let mut t = Table::new(2, &zeros).unwrap();
        let x = Xyz::new(30.0, 20.0, 10.0);
        let plain = d.drive(x, GamutMap::Clip, 255);
        assert_eq!(corrected(&mut t, plain, 255), plain);
    }

    /// The table corrects an interacting display toward its matrix model: the full model at
    /// the corrected values emits the matrix model's colour (nodes from the exact inverse).
    #[test]
    fn corrects_an_interacting_display() {
        let (xy, lum) = Display::srgb().primaries();
        let t = [
            Transfer::Gamma(2.2),
            Transfer::Gamma(2.2),
            Transfer::Gamma(2.2),
        ];
        let matrix = Display::from_primaries(xy, lum, Xyz::default(), t.clone()).unwrap();
        let vals = (0..27).map(|i| {
            let p = [i / 9, i / 3 % 3, i % 3].map(|n| n as f32 / 2.0);
            [
                -0.02 * p[0] * p[1],
                -0.03 * p[1] * p[2],
                -0.01 * p[0] * p[2],
            ]
        });
        let model = DisplayModel::new(
            matrix.clone(),
            Some(Interaction::<27>::new(3, vals).unwrap()),
        );
        let g = 9;
        let nodes: [[i16; 3]; 729] = core::array::from_fn(|i| node(&model, &matrix, g, i));
        let mut table = Table::new(g, &nodes).unwrap();
        let target = Xyz::new(30.0, 30.0, 30.0);
        let plain = matrix.drive(target, GamutMap::Clip, 65535);
        let fixed = corrected(&mut table, plain, 65535);
        let show = |l: [u16; 3]| model.device_to_xyz(l.map(|v| v as f32 / 65535.0));
        let want = target.scale(matrix.white().y / 100.0);
        let err = |x: Xyz| {
            (x.x - want.x)
                .abs()
                .max((x.y - want.y).abs())
                .max((x.z - want.z).abs())
        };
        assert!(err(show(fixed.level)) < 2e-4, "{:?}", show(fixed.level));
        assert!(err(show(plain.level)) > 5e-3);
        assert_eq!(fixed.emitted, plain.emitted);
    }

    #[test]
    fn checksum_and_key_see_every_value() {
        let a = checksum(2, [[1, 2, 3]; 8]);
        let mut n = [[1i16, 2, 3]; 8];
        n[7][2] = 4;
        assert_ne!(a, checksum(2, n));
        assert_ne!(a, checksum(3, [[1, 2, 3]; 8]));
        let (xy, lum) = Display::srgb().primaries();
        let t = [Transfer::Srgb, Transfer::Srgb, Transfer::Srgb];
        let k = calibration_key(xy, lum, &t);
        let mut t2 = t.clone();
        t2[2] = Transfer::Gamma(2.2);
        assert_ne!(k, calibration_key(xy, lum, &t2));
        assert_ne!(k, calibration_key(xy, [lum[0], lum[1], lum[2] * 2.0], &t));
        assert_eq!(k, calibration_key(xy, lum, &t.clone()));
    }
}
