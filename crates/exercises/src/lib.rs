//! Chapter exercises (placeholder; the exercises issue fills this crate).
