"""The linearised stability screen of the time loop (one and two contact points) and the mitigation searches built on it."""
