//! Monte Carlo integration (book 3, chapters 2 and 3): running statistics with standard errors and
//! confidence intervals, and estimators of integrals that return them together with their cost.
//!
//! | estimator | samples | standard error from |
//! |---|---|---|
//! | [`plain`], [`plain_2d`] | uniform on the domain | the `N` samples |
//! | [`importance`] | a user sampler with its pdf | the `N` samples of `f/p` |
//! | [`jittered`], [`jittered_2d`] | one uniform sample per cell | `R` independent replicates |
//! | [`sobol()`], [`sobol_2d`] | Owen-scrambled Sobol points | `R` independent scrambles |
//!
//! Every estimator returns an [`Estimate`] or a [`McError`] naming what was wrong (an empty interval,
//! zero samples, a NaN from the integrand, a pdf of 0 where the integrand is not 0). [`check`] holds the
//! test of an estimate against an exact value that the tests of every crate use.

pub mod check;
pub mod densities;
mod domain;
mod error;
mod estimate;
mod qmc;
pub mod sequence;
mod stats;
mod stratified;

pub use domain::{Interval, Rect};
pub use error::McError;
pub use estimate::{Estimate, importance, plain, plain_2d};
pub use qmc::{sobol, sobol_2d};
pub use stats::{RunningStats, student_t_quantile};
pub use stratified::{jittered, jittered_2d};
