//! The `inspect` command's entry point (being moved here; see ARCHITECTURE.md).
