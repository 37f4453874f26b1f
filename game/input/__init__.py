"""Input devices as one event stream: mouse, touch, keys, gestures, HID trackers, TUIO and recordings."""
