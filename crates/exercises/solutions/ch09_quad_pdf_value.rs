//! Reference solution of `exercises/ch09_quad_pdf_value.rs`, compiled only with `--features solutions`: try the
//! exercise first (`cargo exercises solution ch09_quad_pdf_value` shows it once your code passes).

use glam::DVec3;
use rtl_exercises::ch09_quad_pdf_value::Quad;

pub fn quad_pdf_value(quad: &Quad, origin: DVec3, direction: DVec3) -> f64 {
    let n = quad.u.cross(quad.v);
    let area = n.length();
    let denom = n.dot(direction);
    // Parallel (or degenerate): no hit. Relative threshold, so scale does not matter.
    if denom.abs() <= 1e-12 * area {
        return 0.0;
    }
    let t = n.dot(quad.q - origin) / denom;
    if !(t > 0.0 && t.is_finite()) {
        return 0.0;
    }
    // Planar coordinates of the hit: p = a u + b v, a = w . (p x v), b = w . (u x p), w = n / n.n.
    let p = origin + t * direction - quad.q;
    let w = n / n.length_squared();
    let (a, b) = (w.dot(p.cross(quad.v)), w.dot(quad.u.cross(p)));
    if !((0.0..=1.0).contains(&a) && (0.0..=1.0).contains(&b)) {
        return 0.0;
    }
    let cosine = denom.abs() / area;
    t * t / (cosine * area)
}
