"""The rail's waveguide finite elements, one idea a module (notes and public names: ``solvers.rail.waveguide``)."""
