"""The whole-array numpy turtle and wood mesher that engine/geometry's compiled loops replaced, kept as
the peer benchmarks.mesh measures them against (and checks they agree with)."""
