"""Physics: constants, epochs, frames, orbital elements, ephemeris, dynamics, propagation.

Pure numerical code on floats, numpy arrays and CasADi symbols. It knows no paper, no
screen and no disk cache (checked by the import-linter contracts in ``pyproject.toml``).
"""
