//! Reference solution of `exercises/ch06_scatter_weight.rs`, compiled only with `--features solutions`: try the
//! exercise first (`cargo exercises solution ch06_scatter_weight` shows it once your code passes).

use glam::DVec3;

pub fn scatter_contribution(
    emitted: DVec3,
    attenuation: DVec3,
    scattering_pdf: f64,
    pdf_value: f64,
    incoming: DVec3,
) -> DVec3 {
    let (s, p) = (scattering_pdf, pdf_value);
    if !(p > 0.0 && p.is_finite() && s >= 0.0 && s.is_finite()) {
        return emitted;
    }
    let scattered = attenuation * incoming * (s / p);
    if scattered.is_finite() {
        emitted + scattered
    } else {
        emitted
    }
}
