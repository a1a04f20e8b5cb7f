"""Wheel mode shapes in 3D: geometry, offscreen renders, VTK export, comparison with a reference table."""
