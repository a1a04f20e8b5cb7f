"""Sound radiation: the Thompson-Jones wheel model, the sound power of contact-force histories, the boundary-element check."""
