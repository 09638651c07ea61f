"""The engine trade study: finite-burn loss against thrust-to-weight."""
