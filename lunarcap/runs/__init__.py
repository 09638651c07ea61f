"""Runs: chains of burns solved in order and cached, sweeps, the trade study, the bench."""
