"""What fills the window: the garden game, the modeler mode, the lab, the kiosk and its attract loop."""
