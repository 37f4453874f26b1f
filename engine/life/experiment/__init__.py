"""Layer 4.5, experiment: the educators' lab and sweeps (factors x seeds, summaries)."""
