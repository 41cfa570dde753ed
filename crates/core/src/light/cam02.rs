//! CIECAM02 (CIE 159:2004) forward model to J, M, h, and CAM02-UCS J′a′b′ (Luo, Cui & Li,
//! "Uniform colour spaces based on CIECAM02 colour appearance model", Color Res. Appl. 31, 2006).
//!
//! Only what CIE 224:2017 needs: a white, adapting luminance `L_A`, background `Y_b`, a surround,
//! complete adaptation (`D = 1`, "discounting the illuminant"). Steps (CIE 159:2004 §3):
//! CAT02 `RGB = M_CAT02·XYZ`; `RGB_c = (Y_w/RGB_w)·RGB`; `RGB′ = M_HPE·M_CAT02⁻¹·RGB_c`;
//! `RGB′_a = sgn·400(F_L|RGB′|/100)^0.42 / (27.13 + (F_L|RGB′|/100)^0.42) + 0.1`;
//! `a = R′_a − 12G′_a/11 + B′_a/11`, `b = (R′_a + G′_a − 2B′_a)/9`, `h = atan2(b, a)`;
//! `A = (2R′_a + G′_a + B′_a/20 − 0.305)·N_bb`, `J = 100(A/A_w)^{cz}`;
//! `t = (50000/13)N_cN_cb·e_t·√(a²+b²) / (R′_a + G′_a + 21B′_a/20)`, `e_t = ¼(cos(h + 2) + 3.8)`;
//! `C = t^0.9·√(J/100)·(1.64 − 0.29ⁿ)^0.73`, `M = C·F_L^¼`.
//! CAM02-UCS: `J′ = 1.7J/(1 + 0.007J)`, `M′ = ln(1 + 0.0228M)/0.0228`, `a′ = M′cos h`, `b′ = M′sin h`.
//!
//! `palette` and other crates have no CIECAM02 with `no_std` and f64 for this; it is ~60 lines.

use crate::Mat3;

const M_CAT02: Mat3<f64> = Mat3([
    [0.7328, 0.4296, -0.1624],
    [-0.7036, 1.6975, 0.0061],
    [0.0030, 0.0136, 0.9834],
]);
/// CIE 159:2004's published inverse (6 decimals), as published rather than computed: the
/// published CIECAM02 and TM-30 values are computed with it.
const M_CAT02_INV: Mat3<f64> = Mat3([
    [1.096124, -0.278869, 0.182745],
    [0.454369, 0.473533, 0.072098],
    [-0.009628, -0.005698, 1.015326],
]);
const M_HPE: Mat3<f64> = Mat3([
    [0.38971, 0.68898, -0.07868],
    [-0.22981, 1.18340, 0.04641],
    [0.0, 0.0, 1.0],
]);

/// A surround: `F`, `c`, `N_c` (CIE 159:2004 Table 1).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Surround {
    /// Degree of adaptation factor `F`.
    pub f: f64,
    /// Impact of surround `c`.
    pub c: f64,
    /// Chromatic induction factor `N_c`.
    pub nc: f64,
}

/// The average surround (`F = 1.0`, `c = 0.69`, `N_c = 1.0`).
pub const AVERAGE: Surround = Surround {
    f: 1.0,
    c: 0.69,
    nc: 1.0,
};

/// A CAM02-UCS colour and its CIECAM02 hue angle.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Ucs {
    /// J′.
    pub j: f64,
    /// a′.
    pub a: f64,
    /// b′.
    pub b: f64,
    /// CIECAM02 hue angle h, degrees in [0, 360).
    pub h: f64,
}

impl Ucs {
    /// Euclidean distance ΔE′ in CAM02-UCS.
    pub fn delta_e(&self, o: &Ucs) -> f64 {
        let (dj, da, db) = (self.j - o.j, self.a - o.a, self.b - o.b);
        libm::sqrt(dj * dj + da * da + db * db)
    }
}

/// CIECAM02 for one white and viewing condition, with complete adaptation (`D = 1`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Cam02 {
    gain: [f64; 3],
    fl: f64,
    nbb: f64,
    z: f64,
    n: f64,
    aw: f64,
    surround: Surround,
}

impl Cam02 {
    /// The model for white `xyz_w`, adapting luminance `la` (cd/m²) and background `yb`.
    pub fn new(xyz_w: [f64; 3], la: f64, yb: f64, surround: Surround) -> Self {
        let rgb_w = M_CAT02.apply(xyz_w);
        let gain = rgb_w.map(|c| xyz_w[1] / c);
        let k = 1.0 / (5.0 * la + 1.0);
        let k4 = k * k * k * k;
        let fl = 0.2 * k4 * 5.0 * la + 0.1 * (1.0 - k4) * (1.0 - k4) * libm::cbrt(5.0 * la);
        let n = yb / xyz_w[1];
        let nbb = 0.725 * libm::pow(n, -0.2);
        let z = 1.48 + libm::sqrt(n);
        let mut s = Self {
            gain,
            fl,
            nbb,
            z,
            n,
            aw: 1.0,
            surround,
        };
        let w = s.compressed(xyz_w);
        s.aw = s.achromatic(w);
        s
    }

    fn compressed(&self, xyz: [f64; 3]) -> [f64; 3] {
        let rgb = M_CAT02.apply(xyz);
        let rgb_c = [
            rgb[0] * self.gain[0],
            rgb[1] * self.gain[1],
            rgb[2] * self.gain[2],
        ];
        let rgb_p = M_HPE.apply(M_CAT02_INV.apply(rgb_c));
        rgb_p.map(|v| {
            let x = libm::pow(self.fl * v.abs() / 100.0, 0.42);
            libm::copysign(400.0 * x / (27.13 + x), v) + 0.1
        })
    }

    fn achromatic(&self, c: [f64; 3]) -> f64 {
        (2.0 * c[0] + c[1] + c[2] / 20.0 - 0.305) * self.nbb
    }

    /// CIECAM02 J, M, h of `xyz` (same scale as the white).
    pub fn jmh(&self, xyz: [f64; 3]) -> [f64; 3] {
        let c = self.compressed(xyz);
        let a = c[0] - 12.0 * c[1] / 11.0 + c[2] / 11.0;
        let b = (c[0] + c[1] - 2.0 * c[2]) / 9.0;
        let mut h = libm::atan2(b, a).to_degrees();
        if h < 0.0 {
            h += 360.0;
        }
        let big_a = self.achromatic(c);
        let j = 100.0 * libm::pow((big_a / self.aw).max(0.0), self.surround.c * self.z);
        let et = 0.25 * (libm::cos(h.to_radians() + 2.0) + 3.8);
        let t = (50000.0 / 13.0) * self.surround.nc * self.nbb * et * libm::sqrt(a * a + b * b)
            / (c[0] + c[1] + 21.0 * c[2] / 20.0);
        let chroma = libm::pow(t, 0.9)
            * libm::sqrt(j / 100.0)
            * libm::pow(1.64 - libm::pow(0.29, self.n), 0.73);
        [j, chroma * libm::sqrt(libm::sqrt(self.fl)), h]
    }

    /// CAM02-UCS J′a′b′ (and h) of `xyz`.
    pub fn ucs(&self, xyz: [f64; 3]) -> Ucs {
        let [j, m, h] = self.jmh(xyz);
        let jp = 1.7 * j / (1.0 + 0.007 * j);
        let mp = libm::log1p(0.0228 * m) / 0.0228;
        let hr = h.to_radians();
        Ucs {
            j: jp,
            a: mp * libm::cos(hr),
            b: mp * libm::sin(hr),
            h,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The adopted white maps to J = 100 and almost no colourfulness (complete adaptation; the
    /// published M_HPE's first row sums to 1.00001, which leaves M ≈ 0.006).
    #[test]
    fn white_is_achromatic_and_j_100() {
        let w = [95.05, 100.0, 108.88];
        let m = Cam02::new(w, 100.0, 20.0, AVERAGE);
        let [j, mm, _] = m.jmh(w);
        assert!((j - 100.0).abs() < 1e-9);
        assert!(mm < 0.01, "{mm}");
    }
}
