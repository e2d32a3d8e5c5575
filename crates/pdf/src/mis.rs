//! Multiple importance sampling weights (Veach, "Robust Monte Carlo Methods for Light Transport
//! Simulation", PhD thesis, 1997, chapter 9).
//!
//! A sample drawn from strategy `f` (one of `nf` samples) whose direction strategy `g` (with `ng`
//! samples) could also have produced gets the weight `w_f`; the weights of all strategies sum to 1 for
//! every direction, which keeps the combined estimator unbiased. Both functions return a number in
//! `[0, 1]`, never NaN: 0 when `f` could not have produced the sample (`f_pdf = 0`), 1 when only `f`
//! could.
//!
//! ```
//! use rtl_pdf::{balance_heuristic, power_heuristic};
//! // One light sample and one material sample of the same direction, densities 3 and 1 per steradian.
//! let (light, material) = (3.0, 1.0);
//! assert_eq!(balance_heuristic(1.0, light, 1.0, material), 0.75); // 3 / (3 + 1)
//! let w = power_heuristic(1.0, light, 1.0, material); // 9 / (9 + 1)
//! assert!((w - 0.9).abs() < 1e-15);
//! assert!((w + power_heuristic(1.0, material, 1.0, light) - 1.0).abs() < 1e-15);
//! ```

// ANCHOR: mis
/// The balance heuristic `nf f / (nf f + ng g)`.
#[inline]
pub fn balance_heuristic(nf: f64, f_pdf: f64, ng: f64, g_pdf: f64) -> f64 {
    let (a, b) = (nf * f_pdf, ng * g_pdf);
    weight(a, b, |r| r)
}

/// The power heuristic with exponent 2, `(nf f)^2 / ((nf f)^2 + (ng g)^2)`: sharper than the balance
/// heuristic where one strategy is much better, and Veach's recommendation.
#[inline]
pub fn power_heuristic(nf: f64, f_pdf: f64, ng: f64, g_pdf: f64) -> f64 {
    let (a, b) = (nf * f_pdf, ng * g_pdf);
    weight(a, b, |r| r * r)
}
// ANCHOR_END: mis

/// `h(a) / (h(a) + h(b))` for a monotone `h` with `h(x y) = h(x) h(y)`, computed through the ratio of
/// the smaller to the larger so that huge densities do not overflow to `inf / inf`.
#[inline]
fn weight(a: f64, b: f64, h: impl Fn(f64) -> f64) -> f64 {
    if a.is_nan() || a <= 0.0 {
        return 0.0; // f could not have made this sample (or its density is NaN)
    }
    if b.is_nan() || b <= 0.0 {
        return 1.0;
    }
    if a == b {
        return 0.5; // also covers both infinite
    }
    if a > b {
        1.0 / (1.0 + h(b / a))
    } else {
        let r = h(a / b);
        r / (1.0 + r)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn weights_sum_to_one_and_are_never_nan() {
        let vals = [0.0, 1e-300, 0.3, 1.0, 7.0, 1e300, f64::INFINITY];
        for &f in &vals {
            for &g in &vals {
                for h in [balance_heuristic, power_heuristic] {
                    let (wf, wg) = (h(1.0, f, 1.0, g), h(1.0, g, 1.0, f));
                    assert!((0.0..=1.0).contains(&wf), "w({f}, {g}) = {wf}");
                    if f > 0.0 || g > 0.0 {
                        assert!((wf + wg - 1.0).abs() < 1e-15, "f={f} g={g}: {wf} + {wg}");
                    } else {
                        assert_eq!((wf, wg), (0.0, 0.0));
                    }
                }
            }
        }
        assert_eq!(balance_heuristic(1.0, f64::NAN, 1.0, 1.0), 0.0);
    }

    #[test]
    fn known_values() {
        assert!((balance_heuristic(1.0, 1.0, 1.0, 3.0) - 0.25).abs() < 1e-15);
        assert!((power_heuristic(1.0, 1.0, 1.0, 3.0) - 0.1).abs() < 1e-15);
        assert!((power_heuristic(2.0, 1.0, 1.0, 1.0) - 0.8).abs() < 1e-15);
    }
}
