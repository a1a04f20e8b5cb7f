"""The wheel/rail time loop, one idea a module (notes and public names: ``solvers.timeloop.interaction``)."""
