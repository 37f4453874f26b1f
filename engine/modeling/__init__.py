"""Layer 3, modeling: strokes, lobes, crown growth and region edits that write the L-string; imports layers 0-2 only."""
