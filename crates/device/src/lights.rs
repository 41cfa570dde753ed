//! The built-in lights as moments, computed at build time by `specpoly-core`'s
//! [`Moments::new`] (see build.rs) and compiled in as `const` [`Moments::from_parts`] values,
//! for both observers and both presets: the controller integrates with the core's own
//! [`Moments::xyz`].

use specpoly_core::{Illuminant, Moments, Observer, Paper, Xyz};

include!(concat!(env!("OUT_DIR"), "/lights.rs"));

/// Whether this build carries the observer's moments (CIE 1964 needs feature `observer-1964`).
pub fn has_observer(observer: Observer) -> bool {
    observer == Observer::Cie1931 || cfg!(feature = "observer-1964")
}

/// The table index of (observer, illuminant); an observer not built in falls back to 1931.
fn index(observer: Observer, illuminant: Illuminant) -> usize {
    let o = match observer {
        Observer::Cie1964 if has_observer(observer) => 1,
        _ => 0,
    };
    let i = Illuminant::ALL
        .iter()
        .position(|x| *x == illuminant)
        .unwrap_or(0);
    o * Illuminant::ALL.len() + i
}

/// The moments of the paper preset (2 cubic spans split at 550 nm).
pub fn paper(observer: Observer, illuminant: Illuminant) -> &'static Moments<2, 4, Paper> {
    &PAPER[index(observer, illuminant).min(PAPER.len() - 1)]
}

/// The moments of the default preset (8 uniform cubic spans).
pub fn default(observer: Observer, illuminant: Illuminant) -> &'static Moments<8, 4> {
    &DEFAULT[index(observer, illuminant).min(DEFAULT.len() - 1)]
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn tables_are_the_cores_moments_to_the_bit() {
        for o in Observer::ALL.into_iter().filter(|o| has_observer(*o)) {
            for i in Illuminant::ALL {
                let light = i.tabulated();
                assert_eq!(*paper(o, i), Moments::new(o, &light), "{o:?} {i:?}");
                assert_eq!(*default(o, i), Moments::new(o, &light), "{o:?} {i:?}");
            }
        }
    }
}
