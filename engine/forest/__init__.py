"""Layer 3, forest: GeoMaTree species, divisor-function propagation and landscapes; imports layers 0-2 only."""
