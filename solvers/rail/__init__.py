"""The rail: waveguide FE of the section, wave families and tables, receptances at any head point, the moving Green's function."""
