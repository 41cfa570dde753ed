//! Hero-wavelength sampling in the path tracer ([`crate::path`]): every material's 1 nm
//! tables, bound to a path's wavelengths ([`bind`]), and a scene compiled with them
//! ([`compile`]). The sampled spectrum itself, its density and its light are
//! [`specpoly_spectra::hero`].

use crate::compiled::{Compiled, PerPath};
use crate::error::{Error, Result};
use crate::material::{Coef, Mat};
use crate::scene::{Material, Scene};
use specpoly_core::LAMBDA_MIN;
use specpoly_spectra::hero::{Hero, TABLE};

pub use crate::material::MatTables;

/// The 1 nm tables of every material, in material order.
pub fn tables(materials: &[Material]) -> Vec<MatTables> {
    let table = |n: &Option<specpoly_spectra::spectrum_names::Named>| {
        n.as_ref().map(|n| {
            let t = n.tabulated();
            (0..TABLE)
                .map(|i| [t.at(LAMBDA_MIN as f64 + i as f64) as f32])
                .collect()
        })
    };
    materials
        .iter()
        .map(|m| {
            [
                table(&m.diffuse),
                table(&m.specular),
                table(&m.mirror),
                table(&m.transmission),
            ]
        })
        .collect()
}

/// Binds the materials `mats` to the wavelengths of `u` (every coefficient evaluated there from
/// its table) and returns a path's starting throughput: one at those wavelengths.
pub(crate) fn bind<const N: usize>(
    tables: &[MatTables],
    u: f32,
    mats: &mut [Mat<Hero<N>>],
) -> Hero<N> {
    let lambda = Hero::<N>::wavelengths(u);
    for (m, t) in mats.iter_mut().zip(tables) {
        let coefs: [&mut Option<Coef<Hero<N>>>; 4] = [
            &mut m.diffuse,
            &mut m.specular,
            &mut m.mirror,
            &mut m.transmission,
        ];
        for (c, tab) in coefs.into_iter().zip(t) {
            if let (Some(c), Some(tab)) = (c, tab) {
                c.value = Hero::at(tab, lambda);
            }
        }
    }
    Hero {
        v: [1.0; N],
        lambda,
    }
}

/// `scene` compiled for hero-wavelength sampling with `N` wavelengths per path: the path
/// tracer binds the materials to each path's wavelengths (the Whitted tracer uses the fixed
/// ones).
pub fn compile<const N: usize>(scene: &Scene) -> Result<Compiled<Hero<N>>> {
    if let Some(m) = scene
        .materials
        .iter()
        .find(|m| m.textures.as_ref().is_some_and(|t| t.base.is_some()))
    {
        return Err(Error::Invalid {
            at: format!("material `{}`", m.name),
            why: "a base-colour texture, which hero-wavelength sampling does not bind to a path's wavelengths: use another mode".into(),
        });
    }
    let c = Compiled::<Hero<N>>::new(scene).map_err(Error::Convert)?;
    Ok(c.with_per_path(PerPath {
        tables: tables(&scene.materials),
        bind: bind::<N>,
    }))
}

#[cfg(test)]
mod tests {
    use super::*;
    use specpoly_core::{Observer, Shade};

    /// Averaged over `u`, the estimator of a reflectance's XYZ is the 1 nm sum (unbiased): a
    /// 4096-point stratified average over `u` against the 1 nm reference.
    #[test]
    fn estimator_is_unbiased() {
        let r = specpoly_spectra::spectrum_names::resolve("colorchecker#red")
            .unwrap()
            .remove(0);
        let fl11 = specpoly_spectra::spectrum_names::resolve("FL11")
            .unwrap()
            .remove(0);
        let obs = Observer::Cie1931;
        let light = Hero::<4>::light(obs, &fl11.tabulated());
        let tab = tables(&[Material {
            name: "r".into(),
            diffuse: Some(r.clone()),
            specular: None,
            phong: 1.0,
            mirror: None,
            transmission: None,
            ior: 1.0,
            textures: None,
        }]);
        let k = 4096;
        let mut sum = [0.0f64; 3];
        for i in 0..k {
            let u = (i as f32 + 0.5) / k as f32;
            let v = Hero::<4>::at(tab[0][0].as_ref().unwrap(), Hero::<4>::wavelengths(u));
            let x = v.xyz(&light).to_array();
            for c in 0..3 {
                sum[c] += x[c] as f64 / k as f64;
            }
        }
        let (exact, white) =
            specpoly_core::exact_xyz(obs, &fl11.tabulated(), |nm| r.tabulated().at(nm));
        let _ = white;
        for c in 0..3 {
            let e = exact[c];
            assert!((sum[c] - e).abs() < 0.05, "{c}: {} vs {e}", sum[c]);
        }
    }
}
