// Nothing to draw: this file holds only comments, no statements; a good diagnostic says the model has no geometry (no primitives), rather than failing silently.

/* still nothing here */
