//! Matrix exponential of a small fixed-size matrix by scaling and squaring with a Taylor
//! series (Moler & Van Loan 2003, "Nineteen dubious ways…", method 3), in `f64`.

/// `e^A` for a 4×4 matrix. The matrix is scaled by `2^{-s}` so that its ∞-norm is below
/// ½, the Taylor series is summed to 20 terms (truncation < 1e-25 relative), then squared
/// `s` times. Non-finite input yields a zero matrix (callers validate before).
pub fn expm4(a: &[[f64; 4]; 4]) -> [[f64; 4]; 4] {
    let norm = a
        .iter()
        .map(|r| r.iter().map(|x| libm::fabs(*x)).sum::<f64>())
        .fold(0.0_f64, f64::max);
    if !norm.is_finite() {
        return [[0.0; 4]; 4];
    }
    let mut s = 0u32;
    let mut scale = 1.0;
    while norm * scale > 0.5 && s < 200 {
        scale *= 0.5;
        s += 1;
    }
    let mut x = [[0.0; 4]; 4];
    for (xr, ar) in x.iter_mut().zip(a.iter()) {
        for (xv, av) in xr.iter_mut().zip(ar.iter()) {
            *xv = av * scale;
        }
    }
    // Taylor: E = I + X + X²/2! + …
    let mut e = identity();
    let mut term = identity();
    for k in 1..=20 {
        term = mul(&term, &x);
        let inv = 1.0 / k as f64;
        for row in term.iter_mut() {
            for v in row.iter_mut() {
                *v *= inv;
            }
        }
        for (er, tr) in e.iter_mut().zip(term.iter()) {
            for (ev, tv) in er.iter_mut().zip(tr.iter()) {
                *ev += tv;
            }
        }
    }
    for _ in 0..s {
        e = mul(&e, &e);
    }
    e
}

fn identity() -> [[f64; 4]; 4] {
    let mut m = [[0.0; 4]; 4];
    for (i, row) in m.iter_mut().enumerate() {
        if let Some(v) = row.get_mut(i) {
            *v = 1.0;
        }
    }
    m
}

fn mul(a: &[[f64; 4]; 4], b: &[[f64; 4]; 4]) -> [[f64; 4]; 4] {
    let mut c = [[0.0; 4]; 4];
    for (cr, ar) in c.iter_mut().zip(a.iter()) {
        for (j, cv) in cr.iter_mut().enumerate() {
            let mut s = 0.0;
            for (k, av) in ar.iter().enumerate() {
                s += av * b.get(k).and_then(|r| r.get(j)).copied().unwrap_or(0.0);
            }
            *cv = s;
        }
    }
    c
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rotation_generator_exponentiates_to_rotation() {
        let w = 3.0;
        let a = [
            [0.0, -w, 0.0, 0.0],
            [w, 0.0, 0.0, 0.0],
            [0.0, 0.0, 0.0, 0.0],
            [0.0, 0.0, 0.0, 0.0],
        ];
        let e = expm4(&a);
        assert!((e[0][0] - libm::cos(w)).abs() < 1e-13);
        assert!((e[1][0] - libm::sin(w)).abs() < 1e-13);
        assert!((e[2][2] - 1.0).abs() < 1e-15);
    }
}
