"""Layer 0, base: the error type, crash-safe file writes and strict settings files; imports nothing from engine."""
