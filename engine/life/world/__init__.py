"""Layer 4.3, world: one tree's world (simulation + tree + player's actions) and the garden of up to six trees."""
