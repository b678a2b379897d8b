//! The `compile` command's entry point (being moved here; see ARCHITECTURE.md).
