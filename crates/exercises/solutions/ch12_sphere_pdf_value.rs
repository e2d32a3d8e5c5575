//! Reference solution of `exercises/ch12_sphere_pdf_value.rs`, compiled only with `--features solutions`: try the
//! exercise first (`cargo exercises solution ch12_sphere_pdf_value` shows it once your code passes).

use glam::DVec3;
use std::f64::consts::PI;

pub fn sphere_solid_angle(radius: f64, distance: f64) -> f64 {
    if distance <= radius {
        return 4.0 * PI;
    }
    let sin2 = (radius / distance).powi(2);
    let cos = (1.0 - sin2).sqrt();
    2.0 * PI * sin2 / (1.0 + cos)
}

pub fn sphere_pdf_value(center: DVec3, radius: f64, origin: DVec3, direction: DVec3) -> f64 {
    let oc = center - origin;
    let dist2 = oc.length_squared();
    if dist2 <= radius * radius {
        return 1.0 / (4.0 * PI);
    }
    // The ray hits iff it points towards the centre and passes within the radius of it.
    let along = oc.dot(direction);
    let miss2 = (oc - along * direction).length_squared();
    if along <= 0.0 || miss2 > radius * radius {
        return 0.0;
    }
    1.0 / sphere_solid_angle(radius, dist2.sqrt())
}
