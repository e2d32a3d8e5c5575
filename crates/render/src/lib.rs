//! rtl-render (placeholder)
