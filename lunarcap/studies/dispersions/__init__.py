"""Dispersions: the capture's delta-V budget under execution and navigation errors."""
