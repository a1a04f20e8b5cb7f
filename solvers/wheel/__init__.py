"""The wheel: axisymmetric FE per Fourier harmonic, eigen solver, mode labels, receptances, modal filters, the half-wheelset."""
