//! A hit record as the bits the renderer reads, for tests that compare two ways of finding it.

use rtl_render::hit::Hit;

/// Everything of a hit that the renderer reads, as bits: `t`, the point, the normal, the side and the
/// material.
pub type Record = (u64, [u64; 3], [u64; 3], bool, u32);

/// `h` as the bits it is compared by.
pub fn record(h: Option<Hit>) -> Option<Record> {
    h.map(|h| {
        (
            h.t.to_bits(),
            h.p.to_array().map(f64::to_bits),
            h.normal.to_array().map(f64::to_bits),
            h.front_face,
            h.material.0,
        )
    })
}
