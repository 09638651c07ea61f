"""Optimisation: the finite-burn optimal-control problem, its transcription, verification.

Legendre-Gauss-Radau collocation in CasADi, solved by IPOPT, and an independent
re-propagation that accepts or rejects every solution.
"""
