"""Formats other tools read and write: CCSDS OPM and OEM (KVN), SPICE SPK, burn files.

lunarcap's exchange with the tools analysts check plans with (GMAT, STK, FreeFlyer,
Orekit, SPICE-based viewers). Every file is Moon-centred, in ICRF axes; epochs are TDB
(or UTC on request) through :mod:`lunarcap.physics.epochs`; the rotation to and from
M-MME2000 is :mod:`lunarcap.physics.frames`'s, once.

* :mod:`~lunarcap.exchange.ccsds`: OPM reading (an arrival state), OPM and OEM writing,
  OEM reading, and the OEM's own Lagrange interpolation.
* :mod:`~lunarcap.exchange.spk`: SPK (type 9, Lagrange) writing and reading with SPICE.
* :mod:`~lunarcap.exchange.burn_files`: the attitude (thrust direction) and maneuver CSV
  files, and flying them through the propagator.
* :mod:`~lunarcap.exchange.gmat`: a GMAT script that flies a capture, the gravity file
  (COF) and Moon kernel it reads, running it with ``gmatpy`` and reading its reports.

This package imports :mod:`lunarcap.physics` only (an import-linter contract): the
capture service's writers (:mod:`lunarcap.capture.writers`) hand it re-flown trajectories
as arrays, and :mod:`lunarcap.mission.plan` reads OPM files through it.
"""
