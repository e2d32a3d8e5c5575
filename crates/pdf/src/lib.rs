//! rtl-pdf (placeholder)
