"""Data files of lunarcap, read by their loaders: the paper's printed numbers, the glossary."""
