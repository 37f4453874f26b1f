"""Layer 4.1, form: the interpretation stage (the L-string's ages as lengths, sizes, radii) and its geometry."""
