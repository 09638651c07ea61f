"""Mission: what is asked of the spacecraft (arrival, engine, burns and their targets).

A capture plan is data; the optimiser (:mod:`lunarcap.optim`) turns it into NLPs.
"""
