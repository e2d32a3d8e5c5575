//! The checkpoint reader on arbitrary bytes: a checkpoint or an error, never a panic. Half of the
//! inputs (first byte even) get a valid length field and checksum, so the fuzzer reaches the
//! content checks behind the integrity checks.
#![no_main]
use libfuzzer_sys::fuzz_target;
use rtl_render::checkpoint::{Checkpoint, Fnv1a};

fuzz_target!(|data: &[u8]| {
    let path = std::path::Path::new("fuzz.ckpt");
    let Some((&mode, body)) = data.split_first() else {
        return;
    };
    if mode % 2 == 0 && body.len() >= 20 {
        let mut b = body.to_vec();
        let len = (b.len() + 8) as u64;
        b[12..20].copy_from_slice(&len.to_le_bytes());
        let sum = Fnv1a::hash(&b);
        b.extend_from_slice(&sum.to_le_bytes());
        let _ = Checkpoint::from_bytes(&b, path);
    } else {
        let _ = Checkpoint::from_bytes(body, path);
    }
});
