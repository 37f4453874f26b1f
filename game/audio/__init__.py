"""Sound: the garden's wind, rain, watering can, birds and crickets, chimes and clicks, synthesised with numpy
and played through pygame's mixer by the state of the game (layer 2, beside render and input)."""
