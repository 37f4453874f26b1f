"""The scene's metre, declared once: what the HUD, the journal, exports and the lab convert with."""

METRE = 10.0  # scene units per metre (a game tree 30 units tall is 3 m; glTF and Blender work in metres)
