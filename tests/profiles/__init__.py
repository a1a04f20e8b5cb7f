"""Running-surface profiles: file format and errors, import, standard
profiles, wear, rigid contact point, calibration, the CLI."""
