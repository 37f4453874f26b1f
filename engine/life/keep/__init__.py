"""Layer 4.4, keep: save files (written atomically, read as hostile input) and time away."""
