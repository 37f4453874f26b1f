"""Layer 4.3, world: one tree's world (the only writer of its state: commands, a replayable log, one step loop) and the garden of up to six trees."""
