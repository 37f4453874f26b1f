"""Layer 4, life: the sun/water simulation, the growing tree, saves and the lab; may import every lower layer."""
