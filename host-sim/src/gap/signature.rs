//! Cell signatures of candidate effects and the angle between one effect's signature and
//! another's signature subspace (issue 13; used by [`super::identify`]). Principal angles
//! between subspaces: Björck & Golub (1973), Math. Comp. 27, reduced to one vector and a
//! subspace.

use super::matched::Gaps;

fn dot(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).map(|(x, y)| x * y).sum()
}

/// Angle (degrees) between `d` and the span of `cols` (90 when `d` or the span is empty).
pub fn angle_to_span(d: &[f64], cols: &[Vec<f64>]) -> f64 {
    project(d, cols).0
}

/// `d` against the span of `cols`: the angle (degrees) between them, and the norm of the
/// part of `d` the span leaves (`|d| · sin angle`; `(90, 0)` for a zero `d`, `(90, |d|)` for
/// an empty span).
fn project(d: &[f64], cols: &[Vec<f64>]) -> (f64, f64) {
    let nd = dot(d, d).sqrt();
    if !(nd.is_finite() && nd > 0.0) {
        return (90.0, 0.0);
    }
    // Modified Gram–Schmidt; columns that add nothing new are skipped.
    let mut basis: Vec<Vec<f64>> = vec![];
    for c in cols {
        let n0 = dot(c, c).sqrt();
        if !(n0.is_finite() && n0 > 0.0) || c.len() != d.len() {
            continue;
        }
        let mut v = c.clone();
        for q in &basis {
            let k = dot(&v, q);
            v.iter_mut().zip(q).for_each(|(x, y)| *x -= k * y);
        }
        let n = dot(&v, &v).sqrt();
        if n > 1e-9 * n0 {
            v.iter_mut().for_each(|x| *x /= n);
            basis.push(v);
        }
    }
    // atan2 of the unexplained and the explained parts: accurate near 0° and 90°
    // (acos of a cosine near 1 is not).
    let mut rest = d.to_vec();
    for q in &basis {
        let k = dot(&rest, q);
        rest.iter_mut().zip(q).for_each(|(x, y)| *x -= k * y);
    }
    let proj2: f64 = basis.iter().map(|q| dot(d, q).powi(2)).sum();
    let left = dot(&rest, &rest).sqrt();
    (left.atan2(proj2.sqrt()).to_degrees(), left)
}

/// The weighted signature and subspace of one ranked effect.
#[derive(Debug, Clone, Default)]
pub struct Signature {
    /// `w ∘ (gaps with the effect − baseline gaps)` on the training records.
    pub d: Vec<f64>,
    /// Weighted Jacobian columns.
    pub cols: Vec<Vec<f64>>,
    /// Training records `d` spans (its norm over √records is in total-gap units,
    /// [`Gaps::total`]).
    pub records: usize,
}

impl Signature {
    /// From the fit's training gaps and Jacobian and the baseline's training gaps.
    pub fn new(fitted: &Gaps, jacobian: &[Vec<f64>], baseline: &Gaps) -> Self {
        let w = &baseline.weights;
        if fitted.gaps.len() != baseline.gaps.len() {
            return Signature::default();
        }
        let d = fitted
            .gaps
            .iter()
            .zip(&baseline.gaps)
            .zip(w)
            .map(|((a, b), w)| w * (a - b))
            .collect();
        let cols = jacobian
            .iter()
            .filter(|c| c.len() == w.len())
            .map(|c| c.iter().zip(w).map(|(x, w)| w * x).collect())
            .collect();
        Signature {
            d,
            cols,
            records: fitted.records,
        }
    }

    /// This signature against `other`'s subspace (its Jacobian columns and its own
    /// signature): the angle between them (degrees), and what of this signature that
    /// subspace leaves, in total-gap units (the norm over √records, as [`Gaps::total`]):
    /// the gap that would remain on the training records if `other` stood in for this
    /// effect, to the first order.
    pub fn against(&self, other: &Signature) -> Reach {
        let mut cols = other.cols.clone();
        cols.push(other.d.clone());
        let (angle_deg, left) = project(&self.d, &cols);
        Reach {
            angle_deg,
            residual: left / (self.records.max(1) as f64).sqrt(),
        }
    }
}

/// How far one effect's signature is from another's subspace ([`Signature::against`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Reach {
    /// Angle (degrees) between the signature and the subspace.
    pub angle_deg: f64,
    /// Norm of the part of the signature the subspace leaves (total-gap units).
    pub residual: f64,
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn angles_between_a_signature_and_a_subspace() {
        let d = vec![1.0, 0.0, 0.0];
        assert!(angle_to_span(&d, &[vec![2.0, 0.0, 0.0]]) < 1e-6);
        assert!((angle_to_span(&d, &[vec![0.0, 1.0, 0.0]]) - 90.0).abs() < 1e-6);
        // 45° to one column, inside the span of two.
        assert!((angle_to_span(&d, &[vec![1.0, 1.0, 0.0]]) - 45.0).abs() < 1e-6);
        assert!(angle_to_span(&d, &[vec![1.0, 1.0, 0.0], vec![0.0, 1.0, 0.0]]) < 1e-6);
        assert_eq!(angle_to_span(&[0.0; 3], &[vec![1.0, 0.0, 0.0]]), 90.0);
        assert_eq!(angle_to_span(&d, &[]), 90.0);
    }
}
