"""Modeler tools on the game screen: crown outlines and lobe shaping, region edits and the L-string overlay."""
