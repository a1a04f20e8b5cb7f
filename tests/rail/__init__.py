"""Rail (BV50 / 60E1 waveguide FE) tests; the shared model builders are in pipeline/validation/references/rail.py."""
