"""The capture service every study calls: a plan solved and verified, exported, re-flown.

A plan solved burn by burn (``chain``) or in one NLP (``joint_plan``), the flown capture
written for other tools (``export``, one writer per format in ``writers``) and flown again
open loop (``openloop``) or in GMAT (``gmat_flight``).
"""
