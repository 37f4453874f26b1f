"""Layer 4.1, lineage: parents, generations and families, and breeding two L-systems into a child."""
