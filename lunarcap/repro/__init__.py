"""Reproducibility plumbing: the one place for paths, and the disk cache keyed by code."""
