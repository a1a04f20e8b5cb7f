"""What a listener hears: the receiver's pressure, the calibrated sound, the pass-by."""
