//! rtl-sampling (placeholder)
