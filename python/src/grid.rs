//! The batch path for reflectances on one shared wavelength grid: `XYZ = W r` with the grid's
//! `3 × k` matrix `W` ([`GridWeights`]: each column the colour of a unit spectrum through the
//! representation's own conversion and integration, so `W r` is the per-spectrum colour to f32
//! rounding), then one pass over the rows.
//!
//! - **When.** For colours of single reflectances (not products) of a 2-D batch, when `W` is
//!   kept from an earlier call or the batch has at least `k / 4` rows (building `W` costs `k`
//!   conversions, the per-spectrum path `n`). Otherwise, and whenever anything is off (a dtype
//!   other than float64/float32, a row that is not finite or not a plausible reflectance, a grid
//!   the library refuses, an overflow), [`try_colours`] returns `None` and the caller takes the
//!   per-spectrum path, which raises the same one-line errors as before.
//! - **The rows as the per-spectrum path sees them** ([`GridWeights::reflectance_xyz`]): each
//!   value rounded to f32 (and scaled as the library scales), checked against the same
//!   reflectance bounds, then `W` applied in f64.
//! - **No copies.** A C-contiguous float64 array is read in place (the GIL released, rows in
//!   parallel chunks); other layouts and float32 are copied once.
//! - **Kept matrices.** The last [`KEEP`] matrices (grid, representation, observer and light
//!   compared by value) are kept for the process, a few kB each.

use numpy::{PyArrayDyn, PyArrayMethods, PyUntypedArrayMethods};
use pyo3::prelude::*;
use rayon::prelude::*;
use specpoly_core::Observer;
use specpoly_spectra::colour::Colour;
use specpoly_spectra::grid_weights::GridWeights;
use specpoly_spectra::repr::Repr;
use specpoly_spectra::spectrum_names::Named;
use std::sync::{Arc, Mutex};

/// Matrices kept for later calls.
pub const KEEP: usize = 8;

/// Rows per parallel chunk (about 20 µs of work at 81 samples a row, so a batch of a thousand
/// rows already spreads over the cores).
const CHUNK: usize = 256;

/// What a matrix is for: compared by value (f32 bit patterns).
#[derive(Clone, PartialEq)]
struct Key {
    repr: Repr,
    observer: Observer,
    light_wl: Vec<u32>,
    light_v: Vec<u32>,
    grid: Vec<u32>,
}

fn bits(v: &[f32]) -> Vec<u32> {
    v.iter().map(|x| x.to_bits()).collect()
}

static KEPT: Mutex<Vec<(Key, Arc<GridWeights>)>> = Mutex::new(Vec::new());

/// The kept matrix for `key`, if any.
fn kept(key: &Key) -> Option<Arc<GridWeights>> {
    let kept = KEPT.lock().unwrap_or_else(|p| p.into_inner());
    kept.iter().find(|(k, _)| k == key).map(|(_, w)| w.clone())
}

/// Keeps `w` for `key`, dropping the oldest beyond [`KEEP`].
fn keep(key: Key, w: Arc<GridWeights>) {
    let mut kept = KEPT.lock().unwrap_or_else(|p| p.into_inner());
    if kept.iter().any(|(k, _)| *k == key) {
        return;
    }
    if kept.len() >= KEEP {
        kept.remove(0);
    }
    kept.push((key, w));
}

/// The rows of a float64 or float32 array of shape `(n, k)`, read in place when they can be.
enum F64Rows<'py> {
    InPlace(numpy::PyReadonlyArrayDyn<'py, f64>),
    Copied(Vec<f64>),
}

impl F64Rows<'_> {
    fn data(&self) -> &[f64] {
        match self {
            F64Rows::InPlace(a) => a.as_slice().unwrap_or(&[]),
            F64Rows::Copied(v) => v,
        }
    }
}

/// `values` as `n` rows of `k` float64 values, or `None` (not a 2-D float64/float32 array).
fn rows_of<'py>(values: &Bound<'py, PyAny>, k: usize) -> Option<(F64Rows<'py>, usize)> {
    if let Ok(a) = values.cast::<PyArrayDyn<f64>>() {
        if a.ndim() != 2 || a.shape()[1] != k {
            return None;
        }
        let n = a.shape()[0];
        let r = a.readonly();
        // in place only in row-major order (`as_slice` also accepts column-major)
        if a.is_c_contiguous() && r.as_slice().is_ok() {
            return Some((F64Rows::InPlace(r), n));
        }
        return Some((F64Rows::Copied(r.as_array().iter().copied().collect()), n));
    }
    if let Ok(a) = values.cast::<PyArrayDyn<f32>>() {
        if a.ndim() != 2 || a.shape()[1] != k {
            return None;
        }
        let n = a.shape()[0];
        let r = a.readonly();
        return Some((
            F64Rows::Copied(r.as_array().iter().map(|v| *v as f64).collect()),
            n,
        ));
    }
    None
}

/// `W` with its columns computed in parallel blocks ([`GridWeights::columns`]).
fn weights(
    repr: Repr,
    observer: Observer,
    light: &Named,
    wl: &[f32],
) -> Result<GridWeights, specpoly_core::Error> {
    let lt = light.tabulated();
    let k = wl.len();
    let block = k.div_ceil(rayon::current_num_threads().max(1) * 2).max(8);
    let parts = (0..k.div_ceil(block))
        .into_par_iter()
        .map(|b| GridWeights::columns(repr, observer, &lt, wl, b * block..(b + 1) * block))
        .collect::<Result<Vec<_>, _>>()?;
    Ok(GridWeights::from_columns(observer, &lt, parts))
}

/// The rows of `values` on `wl` by the grid's matrix, each colour mapped by `f` to `k_out`
/// numbers (the first of its three), row-major, computed with the GIL released; or `None` for
/// the per-spectrum path (see the module docs), which checks `values` and `wl` again.
#[allow(clippy::too_many_arguments)]
pub fn try_colours(
    py: Python<'_>,
    values: &Bound<'_, PyAny>,
    wl: &[f32],
    light: &Named,
    observer: Observer,
    repr: Repr,
    scale: f64,
    k_out: usize,
    f: impl Fn(&Colour) -> [f64; 3] + Send + Sync,
) -> Option<(Vec<f64>, usize)> {
    if !(scale.is_finite() && scale > 0.0 && (1..=3).contains(&k_out)) {
        return None;
    }
    let k = wl.len();
    let (rows, n) = rows_of(values, k)?;
    let key = Key {
        repr,
        observer,
        light_wl: bits(&light.wavelengths),
        light_v: bits(&light.values),
        grid: bits(wl),
    };
    let w = match kept(&key) {
        Some(w) => w,
        None if n >= 2 && 4 * n >= k => {
            // the library checks the grid (finite, increasing, reaching 380–780 nm)
            let w = Arc::new(py.detach(|| weights(repr, observer, light, wl)).ok()?);
            keep(key, w.clone());
            w
        }
        None => return None,
    };
    let data = rows.data();
    if data.len() != n * k || k == 0 {
        return None;
    }
    let white = w.white();
    let mut out = vec![0.0; n * k_out];
    let ok = py.detach(|| {
        data.par_chunks(CHUNK * k)
            .zip(out.par_chunks_mut(CHUNK * k_out))
            .all(|(rows, outs)| {
                rows.chunks_exact(k)
                    .zip(outs.chunks_exact_mut(k_out))
                    .all(|(row, o)| match w.reflectance_xyz(row, scale) {
                        Some(xyz) => {
                            o.copy_from_slice(&f(&Colour { xyz, white })[..k_out]);
                            true
                        }
                        None => false,
                    })
            })
    });
    ok.then_some((out, n))
}
