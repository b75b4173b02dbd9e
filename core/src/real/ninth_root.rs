//! `x^{1/9}` in `f64` by range reduction, a short series and one Newton step: the root that
//! the Lundberg/Palmgren line-contact law `Q = K δ^{10/9}` needs for every loaded roller on
//! every step (a roller bearing's life spent more than half its time in the two cube roots
//! it replaces).
//!
//! `x = 2^{9q+r} m` with `m ∈ [1, 2)` and `r ∈ 0..9`, so `x^{1/9} = 2^q · 2^{r/9} · m^{1/9}`;
//! `m` is split into sixteen intervals of centre `c` with `m^{1/9} = c^{1/9} (1+t)^{1/9}`,
//! `t = m/c − 1`, `|t| ≤ 1/33`, where the binomial series to `t⁴` is within `5·10⁻¹⁰`.
//! One Newton step for `y⁹ = x` squares that error away (`4ε² ≈ 10⁻¹⁸`), leaving the
//! rounding of the step itself: within 2 ulp of the exact root (checked against the
//! correctly rounded `cbrt∘cbrt` in the tests below). IEEE operations only, no fused
//! multiply-add: the same bits on every target.

/// `2^{r/9}`, `r = 0..9`.
const TWO_POW_R_9: [f64; 9] = [
    1.0,
    1.080_059_738_892_306,
    1.166_529_039_576_116_5,
    1.259_921_049_894_873_2,
    1.360_790_000_174_377,
    1.469_734_492_275_598_8,
    1.587_401_051_968_199_4,
    1.714_487_965_706_145_6,
    1.851_749_424_574_580_7,
];

/// `1/c` for the centres `c = 1 + (j + ½)/16` of the mantissa's sixteen intervals.
const INV_CENTRE: [f64; 16] = [
    0.969_696_969_696_969_7,
    0.914_285_714_285_714_3,
    0.864_864_864_864_864_9,
    0.820_512_820_512_820_5,
    0.780_487_804_878_048_8,
    0.744_186_046_511_627_9,
    0.711_111_111_111_111_1,
    0.680_851_063_829_787_2,
    0.653_061_224_489_795_9,
    0.627_450_980_392_156_9,
    0.603_773_584_905_660_4,
    0.581_818_181_818_181_8,
    0.561_403_508_771_929_8,
    0.542_372_881_355_932_2,
    0.524_590_163_934_426_3,
    0.507_936_507_936_507_9,
];

/// `c^{1/9}` for the same centres.
const ROOT_CENTRE: [f64; 16] = [
    1.003_424_924_883_145,
    1.010_006_641_446_423_3,
    1.016_262_146_848_769_1,
    1.022_223_992_128_948,
    1.027_920_008_790_633_5,
    1.033_374_186_111_588_4,
    1.038_607_352_750_627_7,
    1.043_637_712_951_546,
    1.048_481_273_150_168_7,
    1.053_152_184_888_498,
    1.057_663_023_053_095_7,
    1.062_025_013_587_064,
    1.066_248_221_333_117,
    1.070_341_706_126_191_3,
    1.074_313_653_384_600_5,
    1.078_171_484_056_394,
];

/// `x^{1/9}` for `x > 0`; zero, subnormal, infinite and NaN arguments are passed to
/// `cbrt(cbrt(x))` (none occurs for a contact deflection: those are normal and positive).
#[inline(always)]
pub(crate) fn ninth_root(x: f64) -> f64 {
    let bits = x.to_bits();
    let biased = (bits >> 52) as i32; // the sign bit is 0 for x > 0
    if !(1..=0x7fe).contains(&biased) {
        return libm::cbrt(libm::cbrt(x));
    }
    let e = biased - 1023;
    let (q, r) = (e.div_euclid(9), e.rem_euclid(9));
    let m = f64::from_bits((bits & 0x000f_ffff_ffff_ffff) | 0x3ff0_0000_0000_0000);
    let j = ((bits >> 48) & 0xf) as usize;
    let (Some(&inv_c), Some(&root_c), Some(&two_r)) = (
        INV_CENTRE.get(j),
        ROOT_CENTRE.get(j),
        TWO_POW_R_9.get(r as usize),
    ) else {
        return libm::cbrt(libm::cbrt(x));
    };
    let t = m * inv_c - 1.0;
    // (1+t)^{1/9} = 1 + t/9 − 4t²/81 + 68t³/2187 − 442t⁴/19683 + …
    let series =
        1.0 + t * (1.0 / 9.0 + t * (-4.0 / 81.0 + t * (68.0 / 2187.0 + t * (-442.0 / 19683.0))));
    // 2^q: |q| ≤ 114, a normal number.
    let two_q = f64::from_bits(((q + 1023) as u64) << 52);
    let y = two_q * (two_r * (root_c * series));
    // Newton for y⁹ = x: y ← y + y (x/y⁹ − 1)/9.
    let y3 = y * y * y;
    y + y * (x / (y3 * y3 * y3) - 1.0) * (1.0 / 9.0)
}

#[cfg(test)]
mod tests {
    use super::ninth_root;

    /// Distance in units in the last place between two positive finite `f64`.
    fn ulps(a: f64, b: f64) -> u64 {
        a.to_bits().abs_diff(b.to_bits())
    }

    /// Within 2 ulp of `cbrt(cbrt(x))` (libm's cube root is correctly rounded, so that
    /// reference is within 0.67 ulp of the exact root) from 10⁻³⁰⁰ to 10³⁰⁰, densely over
    /// the deflections of a loaded roller (10⁻⁹ … 10⁻³ m), and at the interval edges of the
    /// reduction (powers of two, the sixteen mantissa intervals).
    #[test]
    fn within_two_ulp_of_the_exact_root() {
        let mut worst = (0, 0.0);
        let mut check = |x: f64| {
            let d = ulps(ninth_root(x), libm::cbrt(libm::cbrt(x)));
            if d > worst.0 {
                worst = (d, x);
            }
        };
        let mut x = 1e-300;
        while x < 1e300 {
            check(x);
            x *= 1.000_731;
        }
        let mut x = 1e-9;
        while x < 1e-3 {
            check(x);
            x *= 1.000_013_7;
        }
        for e in -1022..1023 {
            for j in 0..=16 {
                let m = 1.0 + f64::from(j) / 16.0;
                let x = m * libm::pow(2.0, f64::from(e));
                check(x);
                check(f64::from_bits(x.to_bits() - 1));
            }
        }
        assert!(worst.0 <= 2, "{} ulp at x = {:e}", worst.0, worst.1);
    }

    /// Exact ninth powers come back exactly, and the fallback takes the arguments that
    /// are not positive normal numbers.
    #[test]
    fn exact_powers_and_edge_arguments() {
        for k in 1..=50 {
            let y = f64::from(k) / 8.0;
            let x = y * y * y * y * y * y * y * y * y;
            assert!(ulps(ninth_root(x), y) <= 1, "{y}");
        }
        assert_eq!(ninth_root(0.0), 0.0);
        assert_eq!(ninth_root(f64::INFINITY), f64::INFINITY);
        assert!(ninth_root(f64::NAN).is_nan());
        let tiny = f64::from_bits(1); // the smallest subnormal, 2^-1074
        assert!(ulps(ninth_root(tiny), libm::cbrt(libm::cbrt(tiny))) <= 2);
    }
}
