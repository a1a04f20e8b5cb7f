"""Where results live and how they are kept: paths, atomic writes, artifacts with provenance, code hashes and Make's dependencies derived from the import graph."""
