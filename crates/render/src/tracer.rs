//! The Whitted ray tracer (Whitted, "An improved illumination model for shaded display",
//! CACM 23(6), 1980), generic over the colour representation `T: Shade` and monomorphised, so
//! every mode runs the same code. An integrator on the compiled scene ([`crate::compiled`]),
//! whose nearest hit, shadow rays and light terms it shares with the path tracer
//! ([`crate::path`]).
//!
//! At a hit with material `(D, S, n, M, F)` the illumination model of the paper (§7) is
//!
//! `I = k_a·D ⊗ L_a + Σ_l v_l·I_l·[(N·L_l) D + (R_l·V)ⁿ S] ⊗ L_l + M·I(reflected) + F·I(refracted)`
//!
//! (Lambertian diffuse, Phong 1975 highlights, mirror and refracted rays), where `⊗ L` means
//! "integrated against light `L`". A path carries its **throughput** `T` — the product of every
//! reflectance and filter met so far, a `Shade` value — and never a light: each light's
//! contribution is `xyz(T · (a·D + b·S), L_l) = a·xyz(T·D, L_l) + b·xyz(T·S, L_l)`, integrated
//! with the light's *exact* precomputed [`Shade::light`] (lights are never fitted, §7.1).
//! XYZ is linear in the spectrum, so at the first hit (`T = 1`) `xyz(D, L_l)` and `xyz(S, L_l)`
//! are precomputed per material and light, and deeper hits form `T·D` and `T·S` once for all
//! lights.
//!
//! Shadow rays see transparent objects as filters: each crossing of a transmitting surface
//! multiplies by its filter `F` (refraction is ignored on the way to the light, as Whitted does);
//! an opaque object blocks. A filter applies at **every** crossing of its surface, so a ray
//! through a solid transparent box is filtered twice (the box is a cell with filter walls).
//! Refraction follows Snell's law with the outside at index 1; total internal reflection sends
//! the transmitted share along the mirror direction.

use crate::compiled::{Compiled, Frame, Surf};
use crate::filter::Filter;
use crate::geometry::Ray;
use specpoly_core::{Shade, Xyz};

/// Adds to `out` the light arriving along `ray` with throughput `tp` (`None` = 1) whose
/// largest value is at most `weight`.
fn trace<T: Shade>(
    c: &Compiled<T>,
    ray: &Ray,
    tp: Option<&T>,
    weight: f32,
    depth: u32,
    out: &mut Xyz,
) {
    let Some((t, normal, surf, tri)) = c.nearest(ray) else {
        *out = *out + c.background(tp);
        // the environment, if any, is seen behind the background
        if let Some(e) = c.environment() {
            *out = *out + c.emitted(tp, &e.light, e.radiance, e.emit_xyz);
        }
        return;
    };
    let mi = match surf {
        Surf::Mat(mi) => mi,
        Surf::Light(k) => {
            let l = &c.area_lights()[k];
            *out = *out + c.emitted(tp, &l.light, l.radiance, l.emit_xyz);
            return;
        }
    };
    // a textured material is formed at the hit; the first-hit tables hold the untextured one
    let textured = c.textured(&c.materials()[mi], mi, tri, ray.at(t), normal);
    let (m, normal) = match &textured {
        Some((m, n)) => (m, *n),
        None => (&c.materials()[mi], normal),
    };
    let tables = textured.is_none();
    let hit = Frame::at(ray, t, normal);
    let Frame { p, n, lift, .. } = hit;

    if m.diffuse.is_some() || m.specular.is_some() {
        let mut acc = Xyz::default();
        let formed = m.times(tp);
        let (td, ts) = (&formed.td, &formed.ts);
        if let Some(x) = c.ambient_term(tables.then_some(mi), m, tp, td.as_ref()) {
            acc = acc + x;
        }
        for (li, l) in c.point_lights().iter().enumerate() {
            let mut scratch = None;
            let Some((filter, a, b)) =
                c.point_weights(c.materials(), &mut scratch, l, m, &hit, p, false)
            else {
                continue;
            };
            let at = (tp.is_none() && tables).then_some((mi, li));
            acc = acc + c.light_term(m, tp, td, ts, &filter, a, b, &l.light, at);
        }
        // area lights: an n × n stratified grid of samples each (deterministic)
        let ns = c.settings().light_samples;
        let inv_n = 1.0 / (ns * ns) as f32;
        for (k, l) in c.area_lights().iter().enumerate() {
            let at = (tp.is_none() && tables).then_some((mi, c.area_slot(k)));
            let (mut a_sum, mut b_sum) = (0.0f32, 0.0f32);
            for i in 0..ns {
                for j in 0..ns {
                    let (u1, u2) = ((i as f32 + 0.5) / ns as f32, (j as f32 + 0.5) / ns as f32);
                    let mut scratch = None;
                    let Some((filter, a, b)) = c.area_weights(
                        c.materials(),
                        &mut scratch,
                        l,
                        m,
                        &hit,
                        (u1, u2),
                        inv_n,
                        false,
                    ) else {
                        continue;
                    };
                    if filter.is_clear() {
                        a_sum += a;
                        b_sum += b;
                    } else {
                        acc = acc + c.light_term(m, tp, td, ts, &filter, a, b, &l.light, at);
                    }
                }
            }
            if a_sum > 0.0 || b_sum > 0.0 {
                let clear = Filter::Clear;
                acc = acc + c.light_term(m, tp, td, ts, &clear, a_sum, b_sum, &l.light, at);
            }
        }
        *out = *out + acc;
    }

    if depth >= c.settings().max_depth {
        return;
    }
    if let Some(mirror) = &m.mirror {
        let w = weight * mirror.max;
        if w >= c.settings().cutoff {
            let r = Ray {
                origin: lift,
                dir: ray.dir.reflect(n),
            };
            let mut formed = None;
            let next = mirror.after_ref(tp, &mut formed);
            trace(c, &r, Some(next), w, depth + 1, out);
        }
    }
    if let Some(filter) = &m.transmission {
        let w = weight * filter.max;
        if w >= c.settings().cutoff {
            let mut formed = None;
            let through = filter.after_ref(tp, &mut formed);
            trace(
                c,
                &hit.through(ray.dir, m.ior),
                Some(through),
                w,
                depth + 1,
                out,
            );
        }
    }
}
/// XYZ of pixel `(x, y)` (white `Y = 100`): the mean over an `n × n` grid of sub-samples.
pub fn pixel<T: Shade>(c: &Compiled<T>, x: u32, y: u32) -> Xyz {
    let s = c.settings();
    let n = s.samples;
    let aspect = s.width as f32 / s.height as f32;
    let mut sum = Xyz::default();
    for sy in 0..n {
        for sx in 0..n {
            let u = (x as f32 + (sx as f32 + 0.5) / n as f32) / s.width as f32;
            let v = (y as f32 + (sy as f32 + 0.5) / n as f32) / s.height as f32;
            let ray = s.camera.ray(u, v, aspect);
            trace(c, &ray, None, 1.0, 0, &mut sum);
        }
    }
    sum.scale(1.0 / (n * n) as f32)
}

/// One row of Whitted-traced pixels into `row` (length `width`).
pub fn row<T: Shade>(c: &Compiled<T>, y: u32, row: &mut [Xyz]) {
    for (x, px) in row.iter_mut().enumerate() {
        *px = pixel(c, x as u32, y);
    }
}
