"""One row per burn: ignition, duration, engine, masses, delta-V and mean direction.

``<stem>_maneuvers.csv`` (:mod:`lunarcap.exchange.burn_files`): the mean direction is
that of the integral of the thrust acceleration over the burn's samples
(:func:`lunarcap.exchange.burn_files.mean_direction`), the delta-V the verified flight's.
"""

from __future__ import annotations

from lunarcap.exchange.burn_files import mean_direction, write_maneuvers


def write(flown) -> dict:
    """Write ``<stem>_maneuvers.csv`` of a :class:`~lunarcap.capture.export.FlownCapture`.

    Returns ``{"maneuvers": path}``.
    """
    rows = []
    for s, smp in zip(flown.solutions, flown.samples):
        rows.append({"t_ign_s": smp["t_s"][0], "duration_s": s.raw.t1_s,
                     "thrust_N": smp["thrust_N"], "isp_s": s.problem.model.isp_s,
                     "m_start_kg": smp["mass_kg"][0], "m_end_kg": smp["mass_kg"][-1],
                     "delta_v_mps": s.flight.delta_v_mps,
                     "dir_icrf": mean_direction(smp["t_s"], smp["u_icrf"], smp["thrust_N"],
                                                smp["mass_kg"])})
    path = flown.path("_maneuvers.csv")
    write_maneuvers(path, rows, flown.time_system)
    return {"maneuvers": path}
