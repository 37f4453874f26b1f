"""Layer 4.2, plant: the sun/water simulation, seasons, light, collisions, the growing tree, roots and its journal."""
