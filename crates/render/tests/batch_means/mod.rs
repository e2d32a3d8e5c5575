//! Batch means compared by Welch's t-test, shared by the renderer's unbiasedness tests.

use statrs::distribution::{ContinuousCDF, StudentsT};

/// The sample mean and the unbiased sample variance.
pub fn mean_var(x: &[f64]) -> (f64, f64) {
    let n = x.len() as f64;
    let m = x.iter().sum::<f64>() / n;
    let v = x.iter().map(|v| (v - m) * (v - m)).sum::<f64>() / (n - 1.0);
    (m, v)
}

// ANCHOR: welch
/// Two-sided p-value of Welch's t-test that two samples of batch means have the same expectation.
/// Two samples without any spread are compared exactly (p = 1 if equal to 1e-12 relative, else 0).
pub fn welch_p(a: &[f64], b: &[f64]) -> f64 {
    let (ma, va) = mean_var(a);
    let (mb, vb) = mean_var(b);
    let (sa, sb) = (va / a.len() as f64, vb / b.len() as f64);
    let se2 = sa + sb;
    if se2 == 0.0 {
        return if (ma - mb).abs() <= 1e-12 * ma.abs().max(mb.abs()) {
            1.0
        } else {
            0.0
        };
    }
    let t = (ma - mb) / se2.sqrt();
    // Welch-Satterthwaite degrees of freedom.
    let df = se2 * se2
        / (sa * sa / (a.len() as f64 - 1.0) + sb * sb / (b.len() as f64 - 1.0))
            .max(f64::MIN_POSITIVE);
    2.0 * StudentsT::new(0.0, 1.0, df).unwrap().sf(t.abs())
}
// ANCHOR_END: welch
