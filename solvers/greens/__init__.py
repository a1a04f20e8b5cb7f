"""Green's functions of receptances (Kropp's method [4.3]-[4.5], the band-limited fit) and the convolutions without the instantaneous term."""
