//! The `render` command's entry point (being moved here; see ARCHITECTURE.md).
