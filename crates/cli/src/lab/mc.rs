//! The Monte Carlo bench (book chapters 2-4): the integrals and estimators of `rtl study mc`, one N at
//! a time, so the page draws the estimate converging with its 95% confidence band while the RMS
//! error against N and against time grows point by point.
//!
//! For `(integral, estimator, N)` the answer is the study's own row ([`measure`]: the RMS error of
//! R = 30 estimates with the study's seeds, their mean standard error, the time per estimate) and the
//! first of those 30 estimates with its Student-t 95% interval: every number is what
//! `rtl study mc` computes for the same N.

use super::params::{BadRequest, Query, bad, bad_param};
use crate::study::mc::{Case, Rng64, cases, measure, seed};
use rand::SeedableRng;
use serde_json::{Value, json};

/// The smallest and largest `log2 N` a request may ask for (the study's `--quick` stops at 16, the
/// full study at 24; 30 estimates of 2^20 samples take about a second on two cores).
pub const LOG2_N: (u32, u32) = (4, 20);

/// The integrals' slugs, in the study's order (its cases come grouped by integral).
fn slugs(all: &[Case]) -> Vec<&'static str> {
    let mut slugs: Vec<&str> = all.iter().map(|c| c.slug).collect();
    slugs.dedup();
    slugs
}

/// The integrals and their estimators, for the page's menus.
pub fn list() -> Value {
    let all = cases();
    let integrals: Vec<Value> = slugs(&all)
        .into_iter()
        .map(|slug| {
            let mine: Vec<&Case> = all.iter().filter(|c| c.slug == slug).collect();
            json!({
                "slug": slug,
                "integral": mine[0].integral,
                "exact": mine[0].exact,
                "estimators": mine.iter().map(|c| c.estimator).collect::<Vec<_>>(),
            })
        })
        .collect();
    json!({ "integrals": integrals, "log2_n": [LOG2_N.0, LOG2_N.1], "repetitions": crate::study::mc::REPETITIONS })
}

/// One point of the convergence: `?integral=SLUG&estimator=NAME&log2_n=K`.
pub fn run(query: &str) -> Result<Value, BadRequest> {
    let q = Query::parse(query, &["integral", "estimator", "log2_n"])?;
    let slug = q.required("integral")?;
    let estimator = q.required("estimator")?;
    let log2_n = q.number("log2_n", 10, LOG2_N.0, LOG2_N.1)?;
    let all = cases();
    if !all.iter().any(|c| c.slug == slug) {
        return Err(bad_param(
            "integral",
            format!(
                "`integral={slug}`: expected one of {}",
                slugs(&all).join(", ")
            ),
        ));
    }
    let Some(index) = all
        .iter()
        .position(|c| c.slug == slug && c.estimator == estimator)
    else {
        let names: Vec<&str> = all
            .iter()
            .filter(|c| c.slug == slug)
            .map(|c| c.estimator)
            .collect();
        return Err(bad_param(
            "estimator",
            format!("`estimator={estimator}`: {slug} has {}", names.join(", ")),
        ));
    };
    let case = &all[index];
    let row = measure(index, case, log2_n).map_err(|e| bad(format!("{e:#}")))?;
    let n = 1u64 << log2_n;
    let first = (case.run)(n, &mut Rng64::seed_from_u64(seed(index, log2_n, 0)))
        .map_err(|e| bad(format!("{e}")))?;
    let (lo, hi) = first
        .confidence_interval(0.95)
        .unwrap_or((f64::NAN, f64::NAN));
    Ok(json!({
        "integral": case.integral,
        "estimator": case.estimator,
        "exact": case.exact,
        "n": row.n,
        "estimate": first.value(),
        "lo": finite(lo),
        "hi": finite(hi),
        "std_error": first.std_error(),
        "rms_error": row.rms_error,
        "mean_std_error": row.mean_std_error,
        "ns_per_sample": row.ns_per_sample,
        "seconds_per_estimate": row.seconds_per_estimate,
    }))
}

fn finite(x: f64) -> Option<f64> {
    x.is_finite().then_some(x)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_point_is_the_studys_row() {
        let v = run("integral=x_sq&estimator=uniform&log2_n=8").unwrap();
        let all = cases();
        let i = all.iter().position(|c| c.slug == "x_sq").unwrap();
        let row = measure(i, &all[i], 8).unwrap();
        assert_eq!(v["rms_error"].as_f64().unwrap(), row.rms_error);
        let (lo, hi) = (v["lo"].as_f64().unwrap(), v["hi"].as_f64().unwrap());
        assert!(lo < v["estimate"].as_f64().unwrap() && v["estimate"].as_f64().unwrap() < hi);
    }

    #[test]
    fn refuses_bad_requests() {
        for q in [
            "integral=nope&estimator=uniform",
            "integral=x_sq&estimator=nope",
            "integral=x_sq&estimator=uniform&log2_n=30",
            "integral=x_sq&estimator=uniform&log2_n=-1",
            "estimator=uniform",
            "integral=x_sq&estimator=uniform&extra=1",
        ] {
            assert!(run(q).is_err(), "{q}");
        }
    }
}
