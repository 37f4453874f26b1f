"""Layer 2, geometry: turtle interpretation, meshing and export; imports engine.base and engine.lsystem."""
