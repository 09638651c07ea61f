"""Missed thrust and late ignition: a capture burn gone wrong, the capture re-planned."""
