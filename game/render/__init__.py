"""Drawing: the moderngl renderer, camera, textures, HUD/menu widgets and charts."""
