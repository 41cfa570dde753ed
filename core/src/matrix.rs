//! A 3×3 matrix for colour-space conversions (row-major, `y = M x`).

use crate::Error;

/// A 3×3 matrix, row-major.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Mat3(pub [[f32; 3]; 3]);

impl Mat3 {
    /// The identity.
    pub const IDENTITY: Mat3 = Mat3([[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]]);

    /// `M x`.
    #[inline]
    pub fn apply(&self, x: [f32; 3]) -> [f32; 3] {
        let m = &self.0;
        [
            m[0][0] * x[0] + m[0][1] * x[1] + m[0][2] * x[2],
            m[1][0] * x[0] + m[1][1] * x[1] + m[1][2] * x[2],
            m[2][0] * x[0] + m[2][1] * x[1] + m[2][2] * x[2],
        ]
    }

    /// `self · o`.
    pub fn mul(&self, o: &Mat3) -> Mat3 {
        let mut r = [[0.0f32; 3]; 3];
        for (i, row) in r.iter_mut().enumerate() {
            for (j, v) in row.iter_mut().enumerate() {
                *v = (0..3)
                    .map(|k| self.0[i][k] as f64 * o.0[k][j] as f64)
                    .sum::<f64>() as f32;
            }
        }
        Mat3(r)
    }

    /// The inverse (computed in f64 by the adjugate), or [`Error::Singular`].
    pub fn inverse(&self) -> Result<Mat3, Error> {
        let m = self.0.map(|r| r.map(|v| v as f64));
        let c = |r0: usize, c0: usize, r1: usize, c1: usize| {
            m[r0][c0] * m[r1][c1] - m[r0][c1] * m[r1][c0]
        };
        let cof = [
            [c(1, 1, 2, 2), -c(1, 0, 2, 2), c(1, 0, 2, 1)],
            [-c(0, 1, 2, 2), c(0, 0, 2, 2), -c(0, 0, 2, 1)],
            [c(0, 1, 1, 2), -c(0, 0, 1, 2), c(0, 0, 1, 1)],
        ];
        let det = m[0][0] * cof[0][0] + m[0][1] * cof[0][1] + m[0][2] * cof[0][2];
        let scale = m.iter().flatten().fold(0.0f64, |a, v| a.max(v.abs()));
        if !det.is_finite() || det.abs() <= 1e-12 * scale * scale * scale {
            return Err(Error::Singular);
        }
        let mut r = [[0.0f32; 3]; 3];
        for (i, row) in r.iter_mut().enumerate() {
            for (j, v) in row.iter_mut().enumerate() {
                *v = (cof[j][i] / det) as f32;
            }
        }
        Ok(Mat3(r))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    #[test]
    fn inverse_roundtrip() {
        let m = Mat3([
            [0.4124, 0.3576, 0.1805],
            [0.2126, 0.7152, 0.0722],
            [0.0193, 0.1192, 0.9505],
        ]);
        let p = m.mul(&m.inverse().unwrap());
        for i in 0..3 {
            for j in 0..3 {
                let e = if i == j { 1.0 } else { 0.0 };
                assert!((p.0[i][j] - e).abs() < 1e-6);
            }
        }
        assert_eq!(
            Mat3([[1.0, 2.0, 3.0], [2.0, 4.0, 6.0], [0.0, 0.0, 1.0]]).inverse(),
            Err(Error::Singular)
        );
    }
}
