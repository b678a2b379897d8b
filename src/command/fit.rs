//! The `fit` command's entry point (being moved here; see ARCHITECTURE.md).
