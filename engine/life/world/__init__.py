"""Layer 4.3, world: one tree's world (the only writer of its own state) and the garden of up to six trees."""
