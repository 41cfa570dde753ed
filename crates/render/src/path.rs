//! A unidirectional path tracer with next-event estimation and Russian roulette (Kajiya, "The
//! rendering equation", SIGGRAPH 1986; Arvo & Kirk, "Particle transport and image synthesis",
//! SIGGRAPH 1990), generic over the colour representation `T: Shade` like the Whitted tracer
//! and sharing its compiled scene, materials and light terms ([`crate::compiled`]).
//!
//! **Closed spectral algebra.** A path carries its throughput `T` — the product of the
//! reflectances and filters met so far — as a value of the representation: a piecewise
//! polynomial multiplied *and degree-reduced* at every bounce, samples, or an RGB triple. Light
//! is never in the path: at every hit each light's contribution is `xyz(T · D, L)` integrated
//! against that light's exact moments. So colour carries no wavelength noise; only the path
//! (directions, light samples, roulette) is random.
//!
//! **Same paths in every mode.** Every random decision uses scalars that do not depend on the
//! representation: the components' largest values over 380–780 nm (as the Whitted tracer's
//! adaptive depth). With the same seed, every mode traces the same rays, so differences between
//! modes are colour error only.
//!
//! At a hit with material `(D, S, n, M, F, η)`:
//! - **direct light** (next-event estimation): point lights as in the Whitted tracer
//!   (`I·cos θ·D + I·(R·V)ⁿ·S`), one sample per area light
//!   (`L_e · [D/π + S·(n+2)/(2π)·(R·V)ⁿ] · cos θ / p(ω)`, see [`crate::lights`]) and one
//!   cosine-distributed sample of the environment (`L_env · D`). Shadow rays pass through
//!   transmitting surfaces of index 1 (filters, multiplied in) and are blocked by refracting
//!   ones;
//! - **continuation**: Lambertian diffuse (cosine sampling: the estimator weight is exactly `D`),
//!   mirror `M` or transmission `F` (Snell's law), chosen with probability proportional to
//!   their largest values `m_D, m_M, m_F`, the throughput multiplied by the chosen coefficient
//!   times `(m_D + m_M + m_F) / m_chosen`. The Phong term lights direct light only;
//! - **Russian roulette** from the third bounce on: a path whose weight bound `w` (the product
//!   of those sums, which bounds the throughput's largest value) is below 1 survives with
//!   probability `w` and is divided by it;
//! - **emission** of area lights and the environment is added when a camera ray, a mirror ray or
//!   a refracted ray meets it (after a diffuse bounce it was counted by next-event estimation).
//!
//! Sampling is deterministic: pixel `(x, y)`, path `s` uses a PCG32 stream (O'Neill 2014,
//! `rand_pcg`) seeded from `(seed, x, y, s)`, so images do not depend on threads.
//!
//! **Hero-wavelength sampling** (`hero:N`, [`crate::hero`]) is the one mode whose values
//! depend on the path: before each path the materials are bound to wavelengths drawn from a
//! second stream (so the path's own stream, hence its rays, stay those of every other mode),
//! into a per-row scratch copy of the materials, and the path starts with throughput one at
//! those wavelengths. Every other mode uses the frame's materials and is unchanged.
//! The ambient term and the background reflectance are Whitted-only.

use crate::compiled::{Compiled, Frame, Surf};
use crate::geometry::Ray;
use crate::lights::cosine_direction;
use crate::material::{Formed, Mat};
use rand_core::Rng;
use rand_pcg::Pcg32;
use specpoly_core::{Shade, Xyz};

/// Mixed into the seed of the stream that draws a path's wavelengths (hero sampling), so the
/// path's own stream, and hence its rays, are those of every other mode.
const WAVELENGTH_STREAM: u64 = 0x6865_726F_5F6C_616D;

/// A deterministic uniform sampler on `[0, 1)`.
pub struct Sampler(Pcg32);

impl Sampler {
    /// The sampler of path `s` of pixel `(x, y)` under `seed` (SplitMix64-style mixing of the
    /// four into the PCG state, the pixel as the stream).
    pub fn new(seed: u64, x: u32, y: u32, s: u32) -> Self {
        let mut z = seed
            ^ (x as u64).wrapping_mul(0x9E37_79B9_7F4A_7C15)
            ^ (y as u64).wrapping_mul(0xC2B2_AE3D_27D4_EB4F)
            ^ (s as u64).wrapping_mul(0x1656_67B1_9E37_79F9);
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^= z >> 31;
        Self(Pcg32::new(z, ((y as u64) << 32) | x as u64))
    }

    /// The next number in `[0, 1)` (24 random bits).
    #[inline]
    pub fn uniform(&mut self) -> f32 {
        (self.0.next_u32() >> 8) as f32 * (1.0 / (1u32 << 24) as f32)
    }
}

/// Which continuation a path took.
#[derive(Clone, Copy, PartialEq)]
enum Bounce {
    Diffuse,
    Mirror,
    Transmit,
}

/// XYZ of pixel `(x, y)` by path tracing: the mean of `spp` paths through uniformly
/// jittered points of the pixel. `scratch` holds the materials bound to a path's
/// wavelengths under hero-wavelength sampling (unused otherwise).
fn pixel<T: Shade>(c: &Compiled<T>, x: u32, y: u32, scratch: &mut [Mat<T>]) -> Xyz {
    let (w, h) = (c.width(), c.height());
    let set = c.settings();
    let aspect = w as f32 / h as f32;
    let mut sum = Xyz::default();
    for s in 0..set.spp {
        let mut rng = Sampler::new(set.seed, x, y, s);
        let u = (x as f32 + rng.uniform()) / w as f32;
        let v = (y as f32 + rng.uniform()) / h as f32;
        let ray = set.camera.ray(u, v, aspect);
        let radiance = match c.per_path() {
            None => path(c, ray, &mut rng, c.materials(), None),
            Some(pp) => {
                // the wavelengths from their own stream: the paths stay those of every mode
                let lambda_u = Sampler::new(set.seed ^ WAVELENGTH_STREAM, x, y, s).uniform();
                let start = (pp.bind)(&pp.tables, lambda_u, scratch);
                path(c, ray, &mut rng, scratch, Some(start))
            }
        };
        sum = sum + radiance;
    }
    sum.scale(1.0 / set.spp as f32)
}

/// The radiance (XYZ) arriving along `ray`.
/// `mats` are the materials (bound to the path's wavelengths under hero sampling) and
/// `start` the starting throughput (`None` = 1).
fn path<T: Shade>(
    c: &Compiled<T>,
    mut ray: Ray,
    rng: &mut Sampler,
    mats: &[Mat<T>],
    start: Option<T>,
) -> Xyz {
    let mut out = Xyz::default();
    let mut tp: Option<T> = start;
    let mut weight = 1.0f32;
    let mut count_emission = true;
    let mut depth = 0u32;
    loop {
        let Some((t, normal, surf, tri)) = c.nearest(&ray) else {
            if let (true, Some(e)) = (count_emission, c.environment()) {
                out = out + c.emitted(tp.as_ref(), &e.light, e.radiance, e.emit_xyz);
            }
            break;
        };
        let mi = match surf {
            Surf::Mat(mi) => mi,
            Surf::Light(k) => {
                if count_emission {
                    let l = &c.area_lights()[k];
                    out = out + c.emitted(tp.as_ref(), &l.light, l.radiance, l.emit_xyz);
                }
                break;
            }
        };
        // a textured material is formed at the hit; the first-hit tables hold the untextured one
        let textured = c.textured(&mats[mi], mi, tri, ray.at(t), normal);
        let (m, normal) = match &textured {
            Some((m, n)) => (m, *n),
            None => (&mats[mi], normal),
        };
        let hit = Frame::at(&ray, t, normal);
        let Frame { n, lift, .. } = hit;

        // `T·D`, formed for direct light, is also the diffuse continuation's throughput
        let lit = m.diffuse.is_some() || m.specular.is_some();
        let formed = if lit {
            m.times(tp.as_ref())
        } else {
            Formed { td: None, ts: None }
        };
        if lit {
            let table = textured.is_none().then_some(mi);
            out = out + direct(c, mats, m, table, tp.as_ref(), &formed, &hit, rng);
        }
        if depth >= c.settings().max_depth {
            break;
        }
        // by reference: a spectral coefficient is 136 bytes
        let md = m.diffuse.as_ref().map_or(0.0, |c| c.max);
        let mm = m.mirror.as_ref().map_or(0.0, |c| c.max);
        let mt = m.transmission.as_ref().map_or(0.0, |c| c.max);
        let total = md + mm + mt;
        if total <= 0.0 {
            break;
        }
        let xi = rng.uniform() * total;
        let (coef, bounce) = match (&m.diffuse, &m.mirror, &m.transmission) {
            (Some(d), _, _) if xi < md => (d, Bounce::Diffuse),
            (_, Some(r), _) if xi < md + mm => (r, Bounce::Mirror),
            (_, _, Some(f)) => (f, Bounce::Transmit),
            (_, Some(r), None) => (r, Bounce::Mirror),
            (Some(d), None, None) => (d, Bounce::Diffuse),
            (None, None, None) => break,
        };
        let bound = weight * total;
        let survive = if depth >= 2 { bound.min(1.0) } else { 1.0 };
        let (u1, u2, u3) = (rng.uniform(), rng.uniform(), rng.uniform());
        if u3 >= survive {
            break;
        }
        let k = total / coef.max / survive;
        tp = Some(match (bounce, &formed.td, k == 1.0) {
            (Bounce::Diffuse, Some(td), true) => *td,
            (Bounce::Diffuse, Some(td), false) => td.scale(k),
            (_, _, true) => coef.after(tp.as_ref()),
            (_, _, false) => coef.after(tp.as_ref()).scale(k),
        });
        weight = bound / survive;
        ray = match bounce {
            Bounce::Diffuse => {
                count_emission = false;
                Ray {
                    origin: lift,
                    dir: cosine_direction(n, u1, u2),
                }
            }
            Bounce::Mirror => {
                count_emission = true;
                Ray {
                    origin: lift,
                    dir: ray.dir.reflect(n),
                }
            }
            Bounce::Transmit => {
                if m.ior != 1.0 {
                    count_emission = true;
                }
                hit.through(ray.dir, m.ior)
            }
        };
        depth += 1;
    }
    out
}

/// Direct light at a hit on material `m` (next-event estimation; see the module docs),
/// with `T·D`, `T·S` formed ([`Mat::times`]); `mi` its index when the first-hit tables hold
/// it (`None` for a textured material).
#[allow(clippy::too_many_arguments)]
fn direct<T: Shade>(
    c: &Compiled<T>,
    mats: &[Mat<T>],
    m: &Mat<T>,
    mi: Option<usize>,
    tp: Option<&T>,
    formed: &Formed<T>,
    hit: &Frame,
    rng: &mut Sampler,
) -> Xyz {
    let Frame { lift, n, .. } = *hit;
    let (td, ts) = (&formed.td, &formed.ts);
    let mut acc = Xyz::default();
    // the first-hit tables hold the frame's materials: not those bound per path (hero)
    let first = tp.is_none() && c.per_path().is_none();
    let first = match (first, mi) {
        (true, Some(mi)) => Some(mi),
        _ => None,
    };
    for (li, l) in c.point_lights().iter().enumerate() {
        let mut scratch = None;
        let Some((filter, a, b)) = c.point_weights(mats, &mut scratch, l, m, hit, lift, true)
        else {
            continue;
        };
        let at = first.map(|mi| (mi, li));
        acc = acc + c.light_term(m, tp, td, ts, &filter, a, b, &l.light, at);
    }
    for (k, l) in c.area_lights().iter().enumerate() {
        let (u1, u2) = (rng.uniform(), rng.uniform());
        let mut scratch = None;
        // share 1.0: `x * 1.0` is exactly `x`
        let Some((filter, a, b)) =
            c.area_weights(mats, &mut scratch, l, m, hit, (u1, u2), 1.0, true)
        else {
            continue;
        };
        let at = first.map(|mi| (mi, c.area_slot(k)));
        acc = acc + c.light_term(m, tp, td, ts, &filter, a, b, &l.light, at);
    }
    if let (Some(e), Some(_)) = (c.environment(), &m.diffuse) {
        let (u1, u2) = (rng.uniform(), rng.uniform());
        let dir = cosine_direction(n, u1, u2);
        let mut scratch = None;
        if let Some(filter) = c.shadow(mats, &mut scratch, lift, dir, f32::INFINITY, true) {
            // (D/π) · L · cos θ / (cos θ / π) = D · L
            acc = acc + c.light_term(m, tp, td, &None, &filter, e.radiance, 0.0, &e.light, None);
        }
    }
    acc
}

/// One row of path-traced pixels into `row` (length `width`).
pub fn row<T: Shade>(c: &Compiled<T>, y: u32, row: &mut [Xyz]) {
    let mut scratch = match c.per_path() {
        Some(_) => c.materials().to_vec(),
        None => Vec::new(),
    };
    for (x, px) in row.iter_mut().enumerate() {
        *px = pixel(c, x as u32, y, &mut scratch);
    }
}
