//! 3D LUTs from a source colour space to a measured display (`calibrate lut3d`): a `N³` grid of
//! encoded source RGB in `[0, 1]` whose nodes hold the device RGB in `[0, 1]` that makes the
//! display, as its model predicts, show the source colour. Video players, graders and capture
//! software apply it with tetrahedral or trilinear interpolation between the nodes.
//!
//! ## The colour a node asks for
//!
//! With `f` the display's full model ([`DisplayModel`]: matrix, curves, interaction lattice),
//! `K = f(0, 0, 0)` its black, `W = f(1, 1, 1)` its white, `S` the source's RGB → XYZ matrix
//! (white `Y = 1`, [`source`]) and `E` its EOTF in relative form, the node of encoded value `c`
//! asks for
//!
//! `XYZ(c) = K + A · S · E(c)`
//!
//! — source black is the display's black, source white is `K + A · S · 1`:
//!
//! - `--white adapt` (default): `A` = Bradford (Lam 1985) from the source white (D65) to the
//!   display's `W − K`, so source white is the display's white `W` (ICC relative
//!   colorimetric; what an eye adapted to the display expects);
//! - `--white keep`: `A = y · I`, the source white's chromaticity kept (absolute colorimetric)
//!   at the largest luminance `y` the display reaches at that chromaticity (at most its white's,
//!   "white point scaling"): no clipping at the white, and greys stay D65.
//!
//! For BT.1886 sources the EOTF is the standard's for the display's own `L_B = K_Y` and
//! `L_W = W_Y`, taken relative (`E = (L − L_B)/(L_W − L_B)`), so a grey's luminance is exactly
//! BT.1886's `L(V)`; its chromaticity moves from the black's to the white's as the display's own
//! does (BT.1886 gives no chromaticity to black, and none darker than `K` exists).
//!
//! ## The gamut
//!
//! A colour is in the gamut when the model's inverse reaches it. A first, cheap test is made in
//! the model's matrix part scaled to its white, `M′ = M · diag(M⁻¹ (W − K))` (so
//! `M′ · 1 = W − K`): `l = M′⁻¹ (XYZ − K)` in `[0, 1]³`. Outside it, `--gamut`:
//!
//! - `clip` (default): each channel of `l` clamped to `[0, 1]` — the clip in device RGB of the
//!   matrix inverse (the curves are monotone, so clamping linear drive is clamping device
//!   values); hue and saturation shift for far-out colours;
//! - `desaturate`: CIELAB (relative to `W`) lightness and hue kept: the colour is moved on the
//!   straight line in a*b* toward the display's grey of the same luminance
//!   (`K + y (W − K)`), to the gamut boundary (bisection, [`DESATURATE_STEPS`] steps), so
//!   out-of-gamut colours lose chroma only.
//!
//! The mapped colour is then inverted through the full model ([`DisplayModel::inverse_with`],
//! the one inverse of the project; module docs of `specpoly_core::display_model`): from the
//! neighbouring node's solution (continuation, [`build`]); a colour mapped onto `M′`'s boundary
//! by its local steps only, as is one whose neighbour was not shown. Where channel interaction
//! makes the full model's gamut smaller than `M′`'s, the inverse does not reach the colour:
//! `clip` takes its local nearest colour (least squares in XYZ over the white's `Y`, within the
//! cube), `desaturate` bisects again toward the grey, the inverse's exactness as the test. Such
//! nodes count as out of gamut ([`Stats`]). Last, the nodes of cells whose colours between
//! the nodes miss are fitted to those colours ([`refine`]; [`Options::refine`]).
//!
//! Every grey of the source (`r = g = b`, which asks for `K + y (W − K)` with `--white adapt`)
//! must be shown: a model whose inverse misses one by more than [`INVERT_LIMIT_DE`] ΔE00 (an
//! interaction lattice that folds the model) is one the LUT cannot be built from — an error,
//! and no file.

pub mod file;
pub mod refine;
pub mod source;

use crate::error::{Error, Result};
use source::{Eotf, SourceSpace};
use specpoly_core::display_model::FULL;
use specpoly_core::{bradford, DisplayModel, InverseOptions, Lab, Mat3, Xyz};

/// The smallest LUT side.
pub const SIZE_MIN: usize = 2;
/// The largest LUT side: 65 is the largest any of the formats' consumers reads (Resolve,
/// eeColor), and `65³` = 274 625 inverses bound the time.
pub const SIZE_MAX: usize = 65;

/// ΔE00 beyond which a grey (source `r = g = b`) counts as not inverted.
pub const INVERT_LIMIT_DE: f64 = 0.5;

/// Bisection steps of the desaturation to the matrix part's boundary (`2⁻²⁰` of the chroma).
pub const DESATURATE_STEPS: usize = 20;
/// Bisection steps of the desaturation to the full model's boundary, each an inverse
/// (`2⁻¹⁰` of the chroma).
pub const MODEL_DESATURATE_STEPS: usize = 10;

/// How the source white is reproduced.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum WhiteMode {
    /// Bradford-adapted to the display's white.
    #[default]
    Adapt,
    /// Kept (absolute), at the largest luminance the display reaches at it.
    Keep,
}

/// How colours outside the display's gamut are brought in.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum GamutMode {
    /// Per channel in linear drive (device RGB).
    #[default]
    Clip,
    /// CIELAB lightness and hue kept, chroma reduced to the boundary.
    Desaturate,
}

impl WhiteMode {
    /// The command-line name.
    pub fn name(self) -> &'static str {
        match self {
            Self::Adapt => "adapt",
            Self::Keep => "keep",
        }
    }
}

impl GamutMode {
    /// The command-line name.
    pub fn name(self) -> &'static str {
        match self {
            Self::Clip => "clip",
            Self::Desaturate => "desaturate",
        }
    }
}

/// What to build.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Options {
    /// The source colour space.
    pub source: SourceSpace,
    /// Nodes per side.
    pub size: usize,
    /// The source white.
    pub white: WhiteMode,
    /// The gamut mapping.
    pub gamut: GamutMode,
    /// Whether the nodes are fitted to the colours between them ([`refine`]); else each node
    /// is its colour's exact inverse.
    pub refine: bool,
}

impl Default for Options {
    fn default() -> Self {
        Self {
            source: SourceSpace::Srgb,
            size: 33,
            white: WhiteMode::Adapt,
            gamut: GamutMode::Clip,
            refine: true,
        }
    }
}

/// The colour each source value asks the display for, and the gamut test and mapping (module
/// docs).
#[derive(Clone, Debug, PartialEq)]
pub struct Target {
    source: SourceSpace,
    white_mode: WhiteMode,
    eotf: Eotf,
    black: [f64; 3],
    white: [f64; 3],
    a_s: Mat3<f64>,
    part: Mat3<f64>,
    part_inv: Mat3<f64>,
    source_white: [f64; 3],
}

fn sub(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

fn add(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[0] + b[0], a[1] + b[1], a[2] + b[2]]
}

fn inside(l: [f64; 3], margin: f64) -> bool {
    l.iter()
        .all(|v| *v >= margin - 1e-6 && *v <= 1.0 - margin + 1e-6)
}

impl Target {
    /// The target for `model` (its units) from `source`, white by `white`.
    pub fn new(model: &DisplayModel<FULL>, source: SourceSpace, white: WhiteMode) -> Result<Self> {
        let k: [f64; 3] = model.device_to_xyz([0.0; 3]).into();
        let w: [f64; 3] = model.white().into();
        let range = sub(w, k);
        if !(range[1] > 0.0) || range.iter().any(|v| !v.is_finite()) {
            return Err(Error::invalid(
                "the display's white",
                format!(
                    "(Y = {}) is not brighter than its black (Y = {})",
                    w[1], k[1]
                ),
            ));
        }
        let m: Mat3<f64> = model.display().rgb_to_xyz().cast();
        let degenerate = || {
            Error::invalid(
                "the display model",
                "has singular primaries: no 3D LUT can be built from it",
            )
        };
        let sigma = m.inverse().map_err(|_| degenerate())?.apply(range);
        if sigma.iter().any(|s| !(s.is_finite() && *s > 0.0)) {
            return Err(Error::invalid(
                "the display model",
                format!(
                    "is not a display: its white is not a positive mix of its primaries (M⁻¹(W − K) = {:.4} {:.4} {:.4})",
                    sigma[0], sigma[1], sigma[2]
                ),
            ));
        }
        let part = m.mul(&Mat3::diagonal(sigma));
        let part_inv = part.inverse().map_err(|_| degenerate())?;
        let s = source.rgb_to_xyz();
        let source_white = s.apply([1.0; 3]);
        let mut t = Target {
            source,
            white_mode: white,
            eotf: source.eotf(k[1], w[1]),
            black: k,
            white: w,
            a_s: s,
            part,
            part_inv,
            source_white,
        };
        let a = match white {
            WhiteMode::Adapt => bradford(Xyz::from_array(source_white), Xyz::from_array(range)),
            WhiteMode::Keep => {
                let y = t.keep_luminance(model);
                Mat3::diagonal([y; 3])
            }
        };
        t.a_s = a.mul(&s);
        Ok(t)
    }

    /// `--white keep`: the largest `y ≤ (W − K)_Y` with `K + y · source white` in the gamut of
    /// `M′`, shrunk (bisection) until the full model's inverse reaches it.
    fn keep_luminance(&self, model: &DisplayModel<FULL>) -> f64 {
        let l = self.part_inv.apply(self.source_white);
        let top = l.iter().cloned().fold(0.0, f64::max);
        let mut y = (self.white[1] - self.black[1]).min(if top > 0.0 { 1.0 / top } else { 1.0 });
        let reaches = |y: f64| {
            let x = add(self.black, self.source_white.map(|v| v * y));
            model.inverse(Xyz::from_array(x.map(|v| v as f32))).exact
        };
        if !reaches(y) {
            let (mut lo, mut hi) = (0.0, y);
            for _ in 0..30 {
                let mid = 0.5 * (lo + hi);
                if reaches(mid) {
                    lo = mid;
                } else {
                    hi = mid;
                }
            }
            y = lo;
        }
        y
    }

    /// The source space.
    pub fn source(&self) -> SourceSpace {
        self.source
    }

    /// The display's white `W = f(1, 1, 1)`, CIELAB's reference white.
    pub fn white(&self) -> [f64; 3] {
        self.white
    }

    /// The display's black `K = f(0, 0, 0)`.
    pub fn black(&self) -> [f64; 3] {
        self.black
    }

    /// The XYZ the source white is shown at.
    pub fn source_white_shown(&self) -> [f64; 3] {
        self.xyz([1.0; 3])
    }

    /// The EOTF used.
    pub fn eotf(&self) -> Eotf {
        self.eotf
    }

    /// The XYZ (display units) the display should show for encoded source RGB `c ∈ [0, 1]³`.
    pub fn xyz(&self, c: [f64; 3]) -> [f64; 3] {
        let lin = c.map(|v| self.eotf.decode(v));
        add(self.black, self.a_s.apply(lin))
    }

    /// The matrix part's linear drive of an XYZ: `M′⁻¹ (XYZ − K)`.
    pub fn drive(&self, xyz: [f64; 3]) -> [f64; 3] {
        self.part_inv.apply(sub(xyz, self.black))
    }

    /// Whether `xyz` is inside the matrix part's gamut.
    pub fn in_gamut(&self, xyz: [f64; 3]) -> bool {
        inside(self.drive(xyz), 0.0)
    }

    /// `xyz` brought into the gamut by `gamut` (module docs), and whether it was outside.
    pub fn map(&self, xyz: [f64; 3], gamut: GamutMode) -> ([f64; 3], bool) {
        let l = self.drive(xyz);
        if inside(l, 0.0) {
            return (xyz, false);
        }
        let clip = |l: [f64; 3]| add(self.black, self.part.apply(l.map(|v| v.clamp(0.0, 1.0))));
        match gamut {
            GamutMode::Clip => (clip(l), true),
            GamutMode::Desaturate => {
                if !self.in_gamut(self.toward_grey(xyz, 0.0)) {
                    // brighter than the white: nothing of its lightness is shown
                    return (clip(l), true);
                }
                (self.desaturate_until(xyz, |x| self.in_gamut(x)), true)
            }
        }
    }

    /// `xyz` moved toward the display's grey of its luminance, `t = 1` itself, `t = 0` the grey
    /// (CIELAB relative to `W`: lightness kept, a*b* on the straight line).
    fn toward_grey(&self, xyz: [f64; 3], t: f64) -> [f64; 3] {
        let w = self.white;
        let range = sub(w, self.black);
        let y = ((xyz[1] - self.black[1]) / range[1]).clamp(0.0, 1.0);
        let grey = add(self.black, range.map(|v| v * y));
        let (lx, lg) = (Lab::from_xyz(xyz, w), Lab::from_xyz(grey, w));
        Lab {
            l: lx.l,
            a: lg.a + t * (lx.a - lg.a),
            b: lg.b + t * (lx.b - lg.b),
        }
        .to_xyz(w)
    }

    /// The most saturated point toward the grey ([`Self::toward_grey`]) that `shown` accepts,
    /// by bisection on `t` ([`DESATURATE_STEPS`] steps; the grey, `t = 0`, if none is).
    pub fn desaturate_until(&self, xyz: [f64; 3], shown: impl Fn([f64; 3]) -> bool) -> [f64; 3] {
        self.desaturate_until_steps(xyz, shown, DESATURATE_STEPS)
    }

    /// [`Self::desaturate_until`] in `steps` bisection steps.
    fn desaturate_until_steps(
        &self,
        xyz: [f64; 3],
        shown: impl Fn([f64; 3]) -> bool,
        steps: usize,
    ) -> [f64; 3] {
        let (mut lo, mut hi) = (0.0, 1.0);
        for _ in 0..steps {
            let mid = 0.5 * (lo + hi);
            if shown(self.toward_grey(xyz, mid)) {
                lo = mid;
            } else {
                hi = mid;
            }
        }
        self.toward_grey(xyz, lo)
    }

    /// The header lines that say how the LUT was made.
    fn describe(&self, opts: &Options) -> Vec<String> {
        let xy = |v: [f64; 3]| {
            let s = v[0] + v[1] + v[2];
            (v[0] / s, v[1] / s)
        };
        let sw = self.source_white_shown();
        let (wx, wy) = xy(self.white);
        let (sx, sy) = xy(sub(sw, self.black));
        let white = match self.white_mode {
            WhiteMode::Adapt => format!(
                "white: adapt: the source white (D65) is adapted to the display's white by Bradford (Lam 1985): shown at the display's white x {wx:.4} y {wy:.4}, Y {:.4}",
                self.white[1]
            ),
            WhiteMode::Keep => format!(
                "white: keep: the source white's chromaticity is kept (absolute colorimetric), x {sx:.4} y {sy:.4}, at the most luminance the display reaches there: Y {:.4} of the display's white {:.4}",
                sw[1], self.white[1]
            ),
        };
        let gamut = match opts.gamut {
            GamutMode::Clip => "gamut: clip: out-of-gamut colours clipped per channel in the display's linear drive (device RGB)",
            GamutMode::Desaturate => "gamut: desaturate: out-of-gamut colours keep their CIELAB lightness and hue and lose chroma toward the display's grey, to the gamut boundary",
        };
        vec![
            format!("source: {}", self.source.description()),
            format!("source EOTF: {}", self.eotf.describe()),
            white,
            format!(
                "black: source black is the display's black, Y {:.6} (luminances in the calibration's units)",
                self.black[1]
            ),
            gamut.into(),
            "input: encoded source RGB 0-1 (full range); output: the display's device RGB 0-1, inverted through the display's model".into(),
        ]
    }
}

/// How a build went.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Stats {
    /// Nodes.
    pub nodes: usize,
    /// Nodes whose colour was outside the gamut and mapped.
    pub out_of_gamut: usize,
    /// Of those, the nodes inside the matrix part's gamut but beyond the full model's (channel
    /// interaction).
    pub beyond_model: usize,
    /// Nodes whose device values do not show their (mapped) colour exactly: the nearest on the
    /// gamut's boundary was taken.
    pub inexact: usize,
    /// The largest ΔE00 of those.
    pub worst_inexact_de: f64,
    /// Nodes fitted to the colours between them ([`refine`]).
    pub refined: usize,
}

/// A built 3D LUT.
#[derive(Clone, Debug, PartialEq)]
pub struct Lut3d {
    size: usize,
    /// Device RGB per node, red fastest: node `(r, g, b)` at `r + N (g + N b)`.
    nodes: Vec<[f64; 3]>,
    /// Per node, whether its colour was in the gamut and shown exactly (built LUTs; empty
    /// for LUTs read from files).
    in_gamut: Vec<bool>,
    title: String,
    header: Vec<String>,
    stats: Stats,
}

impl Lut3d {
    /// A LUT of `size³` nodes (red fastest: `r + N (g + N b)`), each a finite device RGB;
    /// sides 2 to [`file::READ_SIZE_MAX`].
    pub fn from_nodes(size: usize, nodes: Vec<[f64; 3]>, title: &str) -> Result<Self> {
        Self::new_unchecked(size, nodes, title)
            .map_err(|why| Error::invalid(format!("a 3D LUT of side {size}:"), why))
    }

    /// [`Self::from_nodes`] with the reason as text.
    pub(crate) fn new_unchecked(
        size: usize,
        nodes: Vec<[f64; 3]>,
        title: &str,
    ) -> std::result::Result<Self, String> {
        if !(2..=file::READ_SIZE_MAX).contains(&size) {
            return Err(format!("sides are 2–{}", file::READ_SIZE_MAX));
        }
        if nodes.len() != size * size * size {
            return Err(format!(
                "needs {} nodes, not {}",
                size * size * size,
                nodes.len()
            ));
        }
        if let Some((i, n)) = nodes
            .iter()
            .enumerate()
            .find(|(_, n)| n.iter().any(|v| !v.is_finite()))
        {
            return Err(format!("node {i} {n:?} is not a finite number"));
        }
        Ok(Self {
            size,
            nodes,
            in_gamut: Vec::new(),
            title: title.into(),
            header: Vec::new(),
            stats: Stats::default(),
        })
    }

    /// Nodes per side.
    pub fn size(&self) -> usize {
        self.size
    }

    /// The node `(r, g, b)` (indices `0 … N − 1`).
    pub fn node(&self, r: usize, g: usize, b: usize) -> [f64; 3] {
        let n = self.size;
        self.nodes[r + n * (g + n * b)]
    }

    /// Whether the colour of node `(r, g, b)` was inside the display's gamut and shown
    /// exactly; `None` for a LUT read from a file.
    pub fn node_in_gamut(&self, r: usize, g: usize, b: usize) -> Option<bool> {
        let n = self.size;
        self.in_gamut.get(r + n * (g + n * b)).copied()
    }

    /// Whether every node of the cell holding `rgb ∈ [0, 1]³` was inside the gamut and shown
    /// exactly (the interpolation there is between colours the display shows); `None` for a
    /// LUT read from a file.
    pub fn cell_in_gamut(&self, rgb: [f64; 3]) -> Option<bool> {
        let top = (self.size - 1) as f64;
        let i = rgb.map(|v| ((v.clamp(0.0, 1.0) * top).floor() as usize).min(self.size - 2));
        let mut all = true;
        for d in 0..8 {
            all &= self.node_in_gamut(i[0] + (d & 1), i[1] + (d >> 1 & 1), i[2] + (d >> 2))?;
        }
        Some(all)
    }

    /// The title.
    pub fn title(&self) -> &str {
        &self.title
    }

    /// The header lines (how it was made), without comment marks.
    pub fn header(&self) -> &[String] {
        &self.header
    }

    /// How the build went.
    pub fn stats(&self) -> Stats {
        self.stats
    }

    /// The LUT applied to `rgb ∈ [0, 1]³` by tetrahedral interpolation (Kasson et al. 1995:
    /// the cell's diagonal splits it into six tetrahedra, chosen by the order of the fractional
    /// parts), what ffmpeg's `lut3d=interp=tetrahedral` and OpenColorIO's best interpolation do.
    pub fn apply(&self, rgb: [f64; 3]) -> [f64; 3] {
        let top = (self.size - 1) as f64;
        let mut i0 = [0usize; 3];
        let mut f = [0.0; 3];
        for c in 0..3 {
            let x = if rgb[c].is_nan() {
                0.0
            } else {
                rgb[c].clamp(0.0, 1.0) * top
            };
            let i = (x.floor() as usize).min(self.size - 2);
            i0[c] = i;
            f[c] = x - i as f64;
        }
        let at = |dr: usize, dg: usize, db: usize| self.node(i0[0] + dr, i0[1] + dg, i0[2] + db);
        let (fr, fg, fb) = (f[0], f[1], f[2]);
        // (weight, corner) of the four vertices
        let w: [(f64, [f64; 3]); 4] = if fr > fg {
            if fg > fb {
                [
                    (1.0 - fr, at(0, 0, 0)),
                    (fr - fg, at(1, 0, 0)),
                    (fg - fb, at(1, 1, 0)),
                    (fb, at(1, 1, 1)),
                ]
            } else if fr > fb {
                [
                    (1.0 - fr, at(0, 0, 0)),
                    (fr - fb, at(1, 0, 0)),
                    (fb - fg, at(1, 0, 1)),
                    (fg, at(1, 1, 1)),
                ]
            } else {
                [
                    (1.0 - fb, at(0, 0, 0)),
                    (fb - fr, at(0, 0, 1)),
                    (fr - fg, at(1, 0, 1)),
                    (fg, at(1, 1, 1)),
                ]
            }
        } else if fb > fg {
            [
                (1.0 - fb, at(0, 0, 0)),
                (fb - fg, at(0, 0, 1)),
                (fg - fr, at(0, 1, 1)),
                (fr, at(1, 1, 1)),
            ]
        } else if fb > fr {
            [
                (1.0 - fg, at(0, 0, 0)),
                (fg - fb, at(0, 1, 0)),
                (fb - fr, at(0, 1, 1)),
                (fr, at(1, 1, 1)),
            ]
        } else {
            [
                (1.0 - fg, at(0, 0, 0)),
                (fg - fr, at(0, 1, 0)),
                (fr - fb, at(1, 1, 0)),
                (fb, at(1, 1, 1)),
            ]
        };
        [0, 1, 2].map(|c| w.iter().map(|(k, v)| k * v[c]).sum())
    }
}

/// Refuses a side outside [`SIZE_MIN`]`..=`[`SIZE_MAX`].
pub fn check_size(size: usize) -> Result<()> {
    if (SIZE_MIN..=SIZE_MAX).contains(&size) {
        Ok(())
    } else {
        Err(Error::invalid(
            format!("3D LUT size {size}"),
            format!("must be {SIZE_MIN}–{SIZE_MAX} nodes per side (17, 33 and 65 are the usual)"),
        ))
    }
}

/// The node values `(i / (N − 1))` of a side.
fn level(i: usize, n: usize) -> f64 {
    i as f64 / (n - 1) as f64
}

/// What happened to one node.
#[derive(Clone, Copy, Debug, PartialEq)]
struct Node {
    device: [f64; 3],
    /// The inverse's own (f32) device values: the next node's start.
    solved: [f32; 3],
    /// Outside the matrix part's gamut (mapped there).
    mapped: bool,
    /// Inside the matrix part's gamut but beyond the full model's.
    beyond: bool,
    /// The miss in ΔE00 when the device values do not show the (mapped) colour exactly.
    miss: Option<f64>,
}

impl Node {
    /// Whether its colour was in the gamut and is shown exactly.
    fn shown(&self) -> bool {
        !self.mapped && !self.beyond && self.miss.is_none()
    }
}

/// One node (module docs): the colour asked for, mapped into the matrix part's gamut, and
/// inverted through the full model; a colour beyond the full model's gamut is taken to its
/// boundary by the inverse's local solve (`clip`) or toward the grey (`desaturate`).
fn solve_node(
    model: &DisplayModel<FULL>,
    target: &Target,
    gamut: GamutMode,
    c: [f64; 3],
    neighbour: Option<Node>,
) -> Result<Node> {
    let start = neighbour.map(|n| n.solved);
    // the global steps search for a colour the local descent from the neighbour missed: worth
    // it only when the neighbour was itself shown (else this colour, next to one outside the
    // gamut, is outside too, and the search would only confirm it)
    let search = neighbour.is_none_or(|n| n.shown());
    let f32s = |x: [f64; 3]| Xyz::from_array(x.map(|v| v as f32));
    let global = |x: [f64; 3]| {
        model.inverse_with(
            f32s(x),
            InverseOptions {
                start,
                global: search,
            },
        )
    };
    let local = |x: [f64; 3]| {
        model.inverse_with(
            f32s(x),
            InverseOptions {
                start,
                global: false,
            },
        )
    };
    let want = target.xyz(c);
    let (mapped, outside) = target.map(want, gamut);
    let is_grey = c[0] == c[1] && c[1] == c[2];
    let mut beyond = false;
    let sol = if outside {
        // on the matrix part's boundary: the local solve (steps 1–2) is all there is to do
        let sol = local(mapped);
        if !sol.exact && gamut == GamutMode::Desaturate {
            local(target.desaturate_until(mapped, |x| local(x).exact))
        } else {
            sol
        }
    } else {
        let sol = global(mapped);
        if sol.exact || is_grey {
            sol
        } else {
            beyond = true;
            match gamut {
                GamutMode::Clip => local(mapped),
                GamutMode::Desaturate => {
                    let shown = |x: [f64; 3]| local(x).exact || global(x).exact;
                    global(target.desaturate_until_steps(mapped, shown, MODEL_DESATURATE_STEPS))
                }
            }
        }
    };
    let device = sol.device.map(f64::from);
    let cannot = |why: String| {
        Error::invalid(
            format!(
                "the display model cannot invert the colour of source RGB {:.4} {:.4} {:.4}",
                c[0], c[1], c[2]
            ),
            why,
        )
    };
    if device.iter().any(|v| !v.is_finite()) || !sol.delta_e00.is_finite() {
        return Err(cannot(format!(
            "(XYZ {:.4} {:.4} {:.4}): its inverse is not a number; no 3D LUT written",
            mapped[0], mapped[1], mapped[2]
        )));
    }
    if is_grey && !outside && sol.delta_e00 > INVERT_LIMIT_DE {
        return Err(cannot(format!(
            "(XYZ {:.4} {:.4} {:.4}, a grey between its black and white): the nearest it shows is {:.2} ΔE00 off; no 3D LUT written",
            mapped[0], mapped[1], mapped[2], sol.delta_e00
        )));
    }
    Ok(Node {
        device,
        solved: sol.device,
        mapped: outside,
        beyond,
        miss: (!sol.exact).then_some(sol.delta_e00),
    })
}

/// Builds the LUT for `model` (named `display` in its title and header) by `opts` (module
/// docs). The nodes are solved in blocks of blue slices on up to
/// [`std::thread::available_parallelism`] threads (at most 8), from the block's white corner
/// down; each node's inverse starts from its neighbour's solution (red + 1, else green + 1,
/// else blue + 1: continuation). Where the model folds — a curve flat at its foot shows the
/// same colour for a range of device values — neighbouring nodes so stay on one branch of the
/// inverse, the one reached from above (the top of the flat foot): interpolation between nodes
/// then never crosses the flat part, where it would show no light at all.
pub fn build(model: &DisplayModel<FULL>, display: &str, opts: &Options) -> Result<Lut3d> {
    check_size(opts.size)?;
    let target = Target::new(model, opts.source, opts.white)?;
    let n = opts.size;
    let total = n * n * n;
    let threads = std::thread::available_parallelism()
        .map_or(1, |t| t.get())
        .clamp(1, 8)
        .min(n);
    let per = n.div_ceil(threads);
    type Block = Result<Vec<Node>>;
    let blocks: Vec<Block> = std::thread::scope(|s| {
        let handles: Vec<_> = (0..threads)
            .map(|t| {
                let target = &target;
                s.spawn(move || {
                    let slices = t * per..((t + 1) * per).min(n);
                    let (b0, b1) = (slices.start, slices.end);
                    // solved from the block's top (white) down; stored red fastest
                    let len = slices.len() * n * n;
                    let mut out: Vec<Option<Node>> = vec![None; len];
                    let at = |r: usize, g: usize, b: usize| ((b - b0) * n + g) * n + r;
                    for b in slices.rev() {
                        for g in (0..n).rev() {
                            for r in (0..n).rev() {
                                let from = |i: usize| out[i];
                                let start = if r + 1 < n {
                                    from(at(r + 1, g, b))
                                } else if g + 1 < n {
                                    from(at(n - 1, g + 1, b))
                                } else if b + 1 < b1 {
                                    from(at(n - 1, n - 1, b + 1))
                                } else {
                                    None
                                };
                                let c = [r, g, b].map(|j| level(j, n));
                                out[at(r, g, b)] =
                                    Some(solve_node(model, target, opts.gamut, c, start)?);
                            }
                        }
                    }
                    let out: Vec<Node> = out.into_iter().flatten().collect();
                    Ok(out)
                })
            })
            .collect();
        handles
            .into_iter()
            .map(|h| {
                h.join()
                    .unwrap_or_else(|_| Err(Error::invalid("a 3D LUT thread", "panicked")))
            })
            .collect()
    });
    let mut nodes = Vec::with_capacity(total);
    let mut in_gamut = Vec::with_capacity(total);
    let mut stats = Stats {
        nodes: total,
        ..Stats::default()
    };
    for block in blocks {
        for node in block? {
            nodes.push(node.device);
            in_gamut.push(node.shown());
            stats.out_of_gamut += usize::from(node.mapped || node.beyond);
            stats.beyond_model += usize::from(node.beyond);
            if let Some(de) = node.miss {
                stats.inexact += 1;
                stats.worst_inexact_de = stats.worst_inexact_de.max(de);
            }
        }
    }
    if opts.refine {
        stats.refined = refine::refine(model, &target, n, &mut nodes, &in_gamut);
    }
    let title = format!("specpoly: {} to {display}, {n}^3", opts.source.name());
    let mut lut = Lut3d::from_nodes(n, nodes, &title)?;
    let mut header = vec![format!("specpoly calibrate lut3d: display {display}")];
    header.extend(target.describe(opts));
    header.push(format!(
        "nodes: {n}^3 = {total}; {} outside the display's gamut (mapped; {} of them by its channel interaction); {} not reached exactly (the nearest on the gamut boundary, worst {:.3} dE00)",
        stats.out_of_gamut, stats.beyond_model, stats.inexact, stats.worst_inexact_de
    ));
    header.push(if opts.refine {
        format!(
            "nodes fitted to the colours between them: {} nodes of the cells whose centre missed by more than {} dE00",
            stats.refined,
            refine::CELL_DE
        )
    } else {
        "nodes: each the exact inverse of its colour".into()
    });
    lut.header = header;
    lut.in_gamut = in_gamut;
    lut.stats = stats;
    Ok(lut)
}

#[cfg(test)]
mod tests {
    use super::*;
    use specpoly_core::{Display, Transfer};

    fn srgb_display() -> DisplayModel<FULL> {
        let (xy, lum) = Display::srgb().primaries();
        let d = Display::from_primaries(
            xy,
            lum.map(|l| l * 100.0),
            Xyz::default(),
            [Transfer::Srgb, Transfer::Srgb, Transfer::Srgb],
        )
        .unwrap();
        DisplayModel::new(d, None)
    }

    #[test]
    fn an_srgb_display_gets_the_identity_from_srgb() {
        let lut = build(
            &srgb_display(),
            "sRGB",
            &Options {
                size: 5,
                ..Options::default()
            },
        )
        .unwrap();
        for r in 0..5 {
            for g in 0..5 {
                for b in 0..5 {
                    let want = [r, g, b].map(|i| level(i, 5));
                    let got = lut.node(r, g, b);
                    for c in 0..3 {
                        assert!((got[c] - want[c]).abs() < 2e-4, "{want:?} -> {got:?}");
                    }
                }
            }
        }
        assert_eq!(lut.stats().out_of_gamut, 0);
        // tetrahedral interpolation reproduces an affine function exactly
        let affine = Lut3d::from_nodes(
            3,
            (0..27)
                .map(|i| {
                    let c = [i % 3, (i / 3) % 3, i / 9].map(|j| level(j, 3));
                    [0.5 * c[0] + 0.2 * c[1], c[2], 0.1 + 0.3 * c[0] - 0.1 * c[2]]
                })
                .collect(),
            "affine",
        )
        .unwrap();
        let p = [0.3, 0.77, 0.41];
        let want = [0.5 * p[0] + 0.2 * p[1], p[2], 0.1 + 0.3 * p[0] - 0.1 * p[2]];
        let got = affine.apply(p);
        for c in 0..3 {
            assert!((got[c] - want[c]).abs() < 1e-12);
        }
    }

    #[test]
    fn sizes_outside_the_range_are_refused() {
        for n in [0, 1, 66, 1000] {
            let e = check_size(n).unwrap_err().to_string();
            assert!(e.contains(&format!("3D LUT size {n}")), "{e}");
        }
    }

    #[test]
    fn rec2020_is_mapped_into_an_srgb_display() {
        let model = srgb_display();
        let t = Target::new(&model, SourceSpace::Rec2020, WhiteMode::Adapt).unwrap();
        let green = t.xyz([0.0, 1.0, 0.0]);
        assert!(!t.in_gamut(green));
        let (clip, out) = t.map(green, GamutMode::Clip);
        assert!(out && t.in_gamut(clip));
        let (desat, _) = t.map(green, GamutMode::Desaturate);
        assert!(t.in_gamut(desat));
        // desaturate keeps lightness and hue
        let w = t.white();
        let (a, b) = (Lab::from_xyz(green, w), Lab::from_xyz(desat, w));
        assert!((a.l - b.l).abs() < 1e-6);
        assert!((a.b.atan2(a.a) - b.b.atan2(b.a)).abs() < 1e-6);
        // on the boundary: one channel at 1 or 0
        let l = t.drive(desat);
        assert!(
            l.iter().any(|v| v.abs() < 1e-4 || (v - 1.0).abs() < 1e-4),
            "{l:?}"
        );
    }
}
