"""Studies of capture plans: campaigns of independent cases on Dask.

The engine trade study, the number of burns, missed thrust and dispersions, each in its
folder; the sweeps and the benchmark of the paper's cases beside them.
"""
