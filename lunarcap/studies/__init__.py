"""Studies of capture plans: campaigns of independent cases on Dask.

The engine trade study, the number of burns, missed thrust and dispersions, each in its
folder (its campaign module with its :class:`~lunarcap.studies.study.Study`, a
``command.py`` with its command and ``--json`` records, its own quantities in a
``glossary.yaml``), registered by one line each in :data:`lunarcap.studies.registry.STUDIES`;
the Study shape, the campaign runner, the sweeps and the benchmark of the paper's cases
beside them.
"""
