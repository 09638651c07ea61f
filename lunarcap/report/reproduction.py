"""Tables of the reproduction report: every number Song 2011 prints beside ours.

Pure functions of DataFrames and dicts the page (:mod:`lunarcap.report.pages.reproduction_report`)
computes with :mod:`lunarcap.studies.sweeps` and :mod:`lunarcap.capture.chain`; nothing here
solves or integrates.
"""

from __future__ import annotations

import re

import numpy as np

from lunarcap.mission.scenario import paper_engines, paper_scenario
from lunarcap.physics import constants as C
from lunarcap.physics.rocket import burn_duration_estimate_s

_TABLE_QUANTITIES = (
    ("burn duration", "min", "paper_burn_duration_min", "burn_duration_min"),
    ("delta-V", "m/s", "paper_delta_v_mps", "delta_v_mps"),
    ("difference from impulsive", "%", "paper_delta_v_loss_percent",
     "loss_vs_paper_impulse_percent"),
)


def short_where(where: str) -> str:
    """``"Sec. 3.2.1, para 2"`` from ``"Sec. 3.2.1, para 2 ('As shown in ...')"``."""
    return where.split(" ('", 1)[0].split(" (\"", 1)[0]


#: The row of the paper's printed impulse beside ours, named by which impulse is ours: here
#: the closed-form two-body impulse (353.272 m/s for LOI 1); the sweep pages set the
#: impulsive limit in the same dynamics beside it instead (353.110 m/s in full dynamics),
#: under their own label (lunarcap.report.pages.sweep.IMPULSE_ROW_LIMIT).
IMPULSE_ROW_TWO_BODY = "impulse (ours: two-body impulse)"


def paper_tables_long(sweeps: dict, impulsive_dv_mps=None):
    """Every number of the paper's Tables 1-5 and B1 beside ours, one row per number.

    Parameters
    ----------
    sweeps : dict
        ``{(thrust_N, loi): DataFrame}`` from :func:`lunarcap.studies.sweeps.sweep_table` with the
        paper's ignition offsets (columns ``paper_*`` beside ours; ``attrs`` ``thrust_N``,
        ``isp_s``).
    impulsive_dv_mps : sequence of 3 floats, optional
        Our impulsive delta-Vs of LOI 1-3 (m/s), set beside the impulsive rows the paper
        prints in every table.

    Returns
    -------
    pandas.DataFrame
        Columns ``source`` (Table 1 ... B1), ``thrust_N``, ``isp_s``, ``loi``,
        ``start_min``, ``quantity``, ``unit``, ``paper``, ``ours``, ``difference``
        (ours - paper, in ``unit``), ``paper_best`` (the paper marks the row best),
        ``ours_best`` (our smallest delta-V among the paper's offsets), ``verified``.
    """
    import pandas as pd

    from lunarcap.paper import printed as P
    rows = []
    b1 = P.paper_table_b1()
    for (thrust, loi), df in sorted(sweeps.items()):
        src = P.paper_table(thrust, loi).attrs["source"]
        isp = df.attrs.get("isp_s", P.PAPER_ENGINES.get(int(thrust)))
        for r in df[~df.free_start].itertuples(index=False):
            for qty, unit, pcol, ocol in _TABLE_QUANTITIES:
                p, o = float(getattr(r, pcol)), float(getattr(r, ocol))
                if not np.isfinite(p):
                    continue
                rows.append({"source": src, "thrust_N": float(thrust), "isp_s": float(isp),
                             "loi": int(loi), "start_min": float(r.start_min), "quantity": qty,
                             "unit": unit, "paper": p, "ours": o, "difference": o - p,
                             "paper_best": bool(r.paper_best), "ours_best": bool(r.best),
                             "verified": bool(r.verified)})
        # Table B1: transcribed separately, compared with the same solution
        hit = b1[(b1.thrust_N == int(thrust)) & (b1.loi == int(loi))]
        for b in hit.itertuples(index=False):
            m = df[np.isclose(df.start_min, b.start_min) & ~df.free_start]
            if m.empty:
                continue
            r = m.iloc[0]
            for qty, unit, pval, ocol in (("burn duration", "min", b.burn_duration_min,
                                           "burn_duration_min"),
                                          ("delta-V", "m/s", b.delta_v_mps, "delta_v_mps"),
                                          ("difference from impulsive", "%", b.diff_percent,
                                           "loss_vs_paper_impulse_percent")):
                o = float(r[ocol])
                rows.append({"source": "Table B1", "thrust_N": float(thrust),
                             "isp_s": float(isp), "loi": int(loi),
                             "start_min": float(b.start_min), "quantity": qty, "unit": unit,
                             "paper": float(pval), "ours": o, "difference": o - float(pval),
                             "paper_best": True, "ours_best": bool(r["best"]),
                             "verified": bool(r["verified"])})
    if impulsive_dv_mps is not None:
        for loi, (p, o) in enumerate(zip(P.PAPER_IMPULSIVE_DV_MPS, impulsive_dv_mps), 1):
            rows.append({"source": "Tables 1-5, B1 (impulsive)", "thrust_N": np.nan,
                         "isp_s": np.nan, "loi": loi, "start_min": np.nan,
                         "quantity": IMPULSE_ROW_TWO_BODY, "unit": "m/s", "paper": float(p),
                         "ours": float(o), "difference": float(o) - float(p),
                         "paper_best": False, "ours_best": False, "verified": True})
    return pd.DataFrame(rows)


def paper_chain_rows(summaries) -> list[dict]:
    """A chain's :meth:`Solution.summary` dicts with the losses and Eq. (19) of the paper.

    The paper measures every loss against its impulsive delta-Vs (353.272, 254.034 and
    245.363 m/s, from Song et al. 2009c) and estimates each burn's duration with Eq. (19)
    from the same impulsive delta-V and the mass at ignition; so are ours here, for the
    comparison with the numbers of its prose (:func:`quote_equivalents`).

    Parameters
    ----------
    summaries : sequence of dict
        ``Solution.summary()`` of burns 1, 2, 3 of one of the paper's plans.

    Returns
    -------
    list of dict
        Copies with ``loss_vs_paper_impulse_mps``, ``loss_vs_paper_impulse_percent`` (vs the
        paper's impulsive delta-V of
        that burn) and ``eq19_duration_min`` (Eq. (19), corrected 19a, with the paper's
        impulsive delta-V and our mass at ignition) set.
    """
    from lunarcap.paper import printed as P
    out = []
    for s in summaries:
        imp = P.PAPER_IMPULSIVE_DV_MPS[int(s["burn"]) - 1]
        row = dict(s)
        row["loss_vs_paper_impulse_mps"] = s["delta_v_mps"] - imp
        row["loss_vs_paper_impulse_percent"] = 100.0 * (s["delta_v_mps"] - imp) / imp
        row["eq19_duration_min"] = burn_duration_estimate_s(
            s["m_start_kg"], imp, s["thrust_N"], s["isp_s"]) / 60.0
        out.append(row)
    return out


def _key(thrust_N: float) -> str:
    return f"{int(thrust_N)}N"


def _input_equivalents(audit_values: dict | None) -> dict:
    """The paper's inputs, which we take as given (periods, constants, engines)."""
    out: dict = {}
    per = paper_scenario().capture_periods_s
    inp = "input (the paper's value)"
    for n in ("abstract_period_capture1_h", "period_capture1_about_h", "period_capture1_h",
              "period_capture1_about2_h"):
        out[n] = (per[0] / 3600.0, "input: the perilunes are 12.235 h apart")
    for n in ("abstract_period_capture2_h", "period_capture2_about_h", "period_capture2_h",
              "period_capture2_about2_h"):
        out[n] = (per[1] / 3600.0, "input: the perilunes are 3.525 h apart")
    t2b = (audit_values or {}).get("period/final")
    note = "input: the final coast lasts 117.848 min" + (
        f"; the two-body period of a 100 km circular orbit is {t2b:.3f} min"
        if t2b is not None else "")
    for n in ("period_final_about_min", "period_final_min"):
        out[n] = (per[2] / 60.0, note)
    out["mu_moon_km3s2"] = (C.MU_MOON, inp)
    out["mu_earth_km3s2"] = (C.MU_EARTH, inp)
    out["mu_sun_km3s2"] = (C.MU_SUN, "corrected: DE405 value, Standish 1998 (the printed one "
                                     "is ten times too small)")
    out["r_moon_km"] = (C.R_MOON, inp)
    out["lunar_unit_km"] = (C.LU_KM, inp)
    out["j2_moon"] = (C.J2_MOON, inp)
    out["arrival_mass_kg"] = (paper_scenario().mass_kg, inp)
    for j, (t, isp) in enumerate(tuple(paper_engines().items()), 1):
        out[f"engine{j}_thrust_N"] = (t, inp)
        out[f"engine{j}_isp_s"] = (isp, inp)
    for n in ("thrust_direction_bound_lower", "thrust_direction_bound_upper"):
        out[n] = (np.nan, "no equivalent number: the same bounds are used (lunarcap.optim.nlp), "
                          "with |u| = 1 imposed")

    return out


def _chain_equivalents(t: float, s: list, impulsive_final_mass_kg: dict | None) -> dict:
    """Our equivalents of the totals and per-burn numbers of one engine's best chain."""
    from lunarcap.paper import printed as P
    out: dict = {}
    k = _key(t)
    m0 = paper_scenario().mass_kg
    imp_total = float(sum(P.PAPER_IMPULSIVE_DV_MPS))
    loss = [x["loss_vs_paper_impulse_mps"] for x in s]
    pct = [x["loss_vs_paper_impulse_percent"] for x in s]
    dur = [x["burn_duration_min"] for x in s]
    total_pct = 100.0 * sum(loss) / imp_total
    mean_pct = float(np.mean(pct))
    fin = m0 - s[2]["m_end_kg"]
    pct_note = (f"total loss / total impulsive delta-V; the mean of our per-burn "
                f"percentages (the paper's way) is {mean_pct:.2f} %")
    for n in (f"loss_total_{k}_mps", f"loss_total_{k}_mps_recalled"):
        out[n] = (float(sum(loss)), "sum of the three losses vs the paper's impulsive "
                                    "delta-Vs")
    for n in (f"loss_total_{k}_percent", f"loss_total_{k}_percent_recalled",
              f"conclusion_loss_{k}_percent"):
        out[n] = (total_pct, pct_note)
    for n in (f"burn_total_{k}_min",):
        out[n] = (float(sum(dur)), "sum of the three burn durations")
    for n in (f"fuel_finite_{k}_kg", f"fuel_finite_{k}_about_kg"):
        out[n] = (fin, "arrival mass minus our mass after LOI 3")
    out[f"mass_final_{k}_kg"] = (s[2]["m_end_kg"], "mass after LOI 3")
    if impulsive_final_mass_kg and t in impulsive_final_mass_kg:
        imp = m0 - impulsive_final_mass_kg[t]
        out[f"fuel_impulsive_{k}_kg"] = (imp, "two-body impulsive sequence from the "
                                              "arrival mass (rocket equation)")
        out[f"fuel_difference_{k}_kg"] = (fin - imp, "finite minus impulsive propellant")
        out[f"fuel_difference_{k}_percent"] = (100.0 * (fin - imp) / imp,
                                               "100 (finite - impulsive) / impulsive")
    for n in (1, 2, 3):
        x = s[n - 1]
        out[f"loss_loi{n}_{k}_mps"] = (x["loss_vs_paper_impulse_mps"],
                                       "vs the paper's impulsive delta-V")
        out[f"loss_loi{n}_{k}_percent"] = (x["loss_vs_paper_impulse_percent"],
                                           "vs the paper's impulsive delta-V")
        out[f"loss_pct_loi{n}_{k}_summary"] = (x["loss_vs_paper_impulse_percent"],
                                               "vs the paper's impulsive delta-V")
        for nm in (f"burn_loi{n}_{k}_min", f"burn_loi{n}_{k}_summary_min",
                   f"burn_loi{n}_{k}_about_min"):
            out[nm] = (x["burn_duration_min"], "burn duration")
        out[f"mass_after_loi{n}_{k}_kg"] = (x["m_end_kg"], f"mass after LOI {n}")
        out[f"fuel_loi{n}_{k}_about_kg"] = (x["fuel_kg"], f"propellant of LOI {n}")
        if x.get("eq19_duration_min") is not None:
            e19 = float(x["eq19_duration_min"])
            out[f"eq19_loi{n}_{k}_min"] = (e19, "Eq. (19) (corrected 19a) with the "
                                                "paper's impulsive delta-V and our "
                                                "ignition mass")
            out[f"eq19_half_loi{n}_{k}_min"] = (e19 / 2.0, "half of our Eq. (19) estimate")
    if t == 150.0:
        out.update(_chain_150N_equivalents(s))
    return out


def _chain_150N_equivalents(s: list) -> dict:
    """The numbers the paper quotes for its 150 N chain only (Fig. 4, the final orbit)."""
    out: dict = {}
    fin = paper_scenario().mass_kg - s[2]["m_end_kg"]
    dur = [x["burn_duration_min"] for x in s]
    out["fuel_150N_recalled_kg"] = (fin, "arrival mass minus our mass after LOI 3")
    out["fig4_burn_loi1_150N_min"] = (dur[0], "LOI 1 burn duration")
    out["fig4_mass_end_kg"] = (s[2]["m_end_kg"],
                               f"our mass after LOI 3; Fig. 4 shows LOI 1 only, "
                               f"which ends at {s[0]['m_end_kg']:.3f} kg")
    alt = s[2]["rp_end_km"] - C.R_MOON
    for n in ("abstract_final_altitude_km", "final_altitude_km"):
        out[n] = (alt, "perilune altitude reached by LOI 3 (150 N), verified")
    for n in ("abstract_final_inclination_deg", "final_inclination_deg"):
        out[n] = (s[2]["inc_end_deg"], "inclination reached by LOI 3 (150 N)")
    return out


def chain_totals_percent(s: list) -> float:
    """Total loss of a chain over the paper's total impulsive delta-V, %."""
    from lunarcap.paper import printed as P
    return (100.0 * sum(x["loss_vs_paper_impulse_mps"] for x in s)
            / float(sum(P.PAPER_IMPULSIVE_DV_MPS)))


def quote_equivalents(chains: dict, impulsive_final_mass_kg: dict | None = None,
                      best_starts: dict | None = None, fig4=None,
                      audit_values: dict | None = None) -> dict:
    """Our number equivalent to each number of the paper's prose, where one exists.

    Parameters
    ----------
    chains : dict
        ``{thrust_N: [row_1, row_2, row_3]}``: the best chain of each engine (the paper's
        best ignition offsets), :meth:`Solution.summary` dicts with the paper's losses
        and Eq. (19) set by :func:`paper_chain_rows`.
    impulsive_final_mass_kg : dict, optional
        ``{thrust_N: kg}``: mass after our impulsive sequence (same arrival mass and Isp).
    best_starts : dict, optional
        ``{(thrust_N, loi): min}``: our best ignition offset among the paper's.
    fig4 : Fig4Steering, optional
        The 150 N LOI-1 steering (:func:`fig4_steering`).
    audit_values : dict, optional
        ``{finding id: computed value}`` from :func:`lunarcap.paper.audit.audit_findings`
        (used for the two-body period of the 100 km orbit).

    Returns
    -------
    dict
        ``{quote name: (value, note)}`` in the quote's unit; names missing have no
        equivalent (or were not computed in this run).
    """
    from lunarcap.paper import printed as P
    out = _input_equivalents(audit_values)
    totals_pct, fuel_fin = {}, {}
    for t, chain in chains.items():
        t, s = float(t), list(chain)
        if len(s) != 3:
            continue
        totals_pct[t] = chain_totals_percent(s)
        fuel_fin[t] = paper_scenario().mass_kg - s[2]["m_end_kg"]
        out.update(_chain_equivalents(t, s, impulsive_final_mass_kg))
    if 150.0 in fuel_fin and 300.0 in fuel_fin:
        out["fuel_saving_300N_vs_150N_kg"] = (fuel_fin[150.0] - fuel_fin[300.0],
                                              "propellant of 150 N minus 300 N")
    if totals_pct:
        tmax = max(totals_pct, key=totals_pct.get)
        for n in ("abstract_max_loss_percent", "conclusion_max_loss_percent"):
            out[n] = (totals_pct[tmax], f"largest total loss ({tmax:g} N), total loss / total "
                                        "impulsive delta-V")
    for (t, loi), start in (best_starts or {}).items():
        name = f"best_start_loi{loi}_{_key(t)}_min"
        if name in P.QUOTES:
            sign = -1.0 if P.QUOTES[name].value > 0 else 1.0  # printed as minutes before
            out[name] = (sign * float(start), "our best of the paper's ignition offsets")
    if fig4 is not None:
        out["fig4_alpha_start_deg"] = (float(fig4.alpha_deg[0]), "α at LOI-1 ignition")
        out["fig4_alpha_end_deg"] = (float(fig4.alpha_deg[-1]), "α at LOI-1 cutoff")
        out["fig4_beta_deg"] = (float(np.abs(fig4.beta_deg).max()),
                                "largest |β| during LOI 1")
        out["fig4_mass_start_kg"] = (float(fig4.m_kg[0]), "mass at LOI-1 ignition")
    return {k: v for k, v in out.items() if k in P.QUOTES}


def quotes_comparison(ours: dict):
    """Every number of the paper's prose (:data:`lunarcap.paper.printed.QUOTES`) beside ours.

    Parameters
    ----------
    ours : dict
        ``{quote name: (value, note)}`` from :func:`quote_equivalents`.

    Returns
    -------
    pandas.DataFrame
        Columns ``name``, ``where`` (section and paragraph), ``text`` (the printed words),
        ``printed`` (as printed), ``paper`` (value), ``unit``, ``ours``, ``difference``
        (ours - paper; NaN without an equivalent), ``note`` ("no equivalent" where none).
    """
    import pandas as pd

    from lunarcap.paper import printed as P
    rows = []
    for q in P.QUOTES.values():
        val, note = ours.get(q.name, (np.nan, "no equivalent"))
        val = float(val)
        rows.append({"name": q.name, "where": short_where(q.where), "text": q.text,
                     "printed": q.printed, "paper": q.value, "unit": q.unit, "ours": val,
                     "difference": val - q.value if np.isfinite(val) else np.nan,
                     "note": note})
    return pd.DataFrame(rows)


def epochs_comparison(perilune_epochs_s):
    """The perilune epochs the paper prints (Sec. 3.2.1) beside our nominal ones.

    Parameters
    ----------
    perilune_epochs_s : sequence of float
        Our nominal perilune epochs, TDB s past J2000 (``Mission.perilune_epochs_s``).

    Returns
    -------
    pandas.DataFrame
        Columns ``perilune``, ``where``, ``paper`` (as printed), ``ours`` (TDB calendar),
        ``difference_s`` (ours - paper, s).
    """
    import pandas as pd

    from lunarcap.paper import printed as P
    from lunarcap.physics.epochs import calendar_from_seconds, seconds_from_calendar

    months = {"Jan": 1, "Feb": 2, "Mar": 3, "Apr": 4, "May": 5, "Jun": 6, "Jul": 7,
              "Aug": 8, "Sep": 9, "Oct": 10, "Nov": 11, "Dec": 12}
    rows = []
    for n, text in P.PAPER_EPOCHS_TDB.items():
        d, mon, rest = text.split("-", 2)
        y, hms = rest.split()[:2]
        t_p = seconds_from_calendar(f"{y}-{months[mon]:02d}-{int(d):02d} {hms} TDB")
        t_o = float(perilune_epochs_s[n - 1])
        rows.append({"perilune": n, "where": short_where(P.PAPER_EPOCHS_WHERE[n]),
                     "paper": text, "ours": calendar_from_seconds(t_o, decimals=0),
                     "difference_s": t_o - t_p})
    return pd.DataFrame(rows)


def _fmt_decimals(v: float, decimals: int, sign: bool = False) -> str:
    if not np.isfinite(v):
        return "—"
    if abs(v) >= 1e6:   # large numbers (gravitational parameters): grouped, one decimal
        decimals = 1
    text = f"{v:{'+' if sign else ''},.{max(0, decimals)}f}"
    if sign and text[1:].replace("0", "").replace(".", "").replace(",", "") == "":
        text = text[1:]  # no "+0.00" / "-0.00"
    return text


def quotes_display(quotes, max_words: int = 24, extra_decimals: int = 1,
                   min_decimals: int = 3):
    """A compact, readable version of :func:`quotes_comparison` for the page.

    Parameters
    ----------
    quotes : DataFrame from :func:`quotes_comparison`
    max_words : int
        The printed words are cut to this many characters (with "…"): enough to find
        the sentence in the paper, whose full words are in the long-form table.
    extra_decimals, min_decimals : int
        Ours and the difference are shown with this many more decimals than printed, and
        at least ``min_decimals``.

    Returns
    -------
    pandas.DataFrame
        String columns ``words`` (where, as ``§3.2.1 ¶2`` for "Sec. 3.2.1, para 2", then
        the words), ``printed`` (with unit), ``ours`` and ``difference`` (ours - printed,
        same unit), ``note``.
    """
    import pandas as pd

    from lunarcap.paper import printed as P
    rows = []
    for r in quotes.itertuples(index=False):
        q = P.QUOTES[r.name]
        dec = max(q.decimals + extra_decimals, min_decimals)
        words = r.text if len(r.text) <= max_words else r.text[:max_words - 1].rstrip() + "…"
        unit = f" {r.unit}" if r.unit else ""
        where = r.where.replace("Sec. ", "§").replace(", para ", " ¶")
        rows.append({"words": f"{where}: {words}", "printed": f"{r.printed}{unit}",
                     "ours": _fmt_decimals(r.ours, dec),
                     "difference": _fmt_decimals(r.difference, dec, sign=True),
                     "note": r.note})
    return pd.DataFrame(rows)


def findings_display(findings):
    """A compact version of :func:`lunarcap.paper.audit.findings_table` for the page.

    Parameters
    ----------
    findings : DataFrame from :func:`lunarcap.paper.audit.findings_table`

    Returns
    -------
    pandas.DataFrame
        String columns ``finding`` (group letter and id, e.g. ``"a: sun-gm"``),
        ``printed`` and ``computed`` (6 significant digits, or grouped digits with one
        decimal from 10^6 up, with the unit) and
        ``explanation`` (where the number is printed, then the first sentence of how it
        was checked: the computation; the reasoning that follows it is in the long-form
        table, which the page links).
    """
    import pandas as pd

    def num(v, unit):
        # 6 significant digits; large numbers (gravitational parameters) grouped in full
        text = f"{v:,.1f}" if abs(v) >= 1e6 else f"{v:.6g}"
        return text + (f" {unit}" if unit else "")

    return pd.DataFrame({
        "finding": [f"{c}: {i}" for c, i in zip(findings.check, findings.id)],
        "printed": [num(v, u) for v, u in zip(findings.printed, findings.unit)],
        "computed": [num(v, u) for v, u in zip(findings.computed, findings.unit)],
        "explanation": [f"{short_where(w)}. {first_sentence(e)}"
                        for w, e in zip(findings["where"], findings.explanation)],
    })


#: The end of a sentence: a full stop after a word, a number or a bracket, then a capital
#: ("Eq. (19)" and "Sec. 3.1" do not end one).
_SENTENCE_END = re.compile(r"(?<=[a-z0-9)%²])\. (?=[A-Z])")


def first_sentence(text: str) -> str:
    """The first sentence of ``text``, with its full stop.

    >>> first_sentence("150 N x 19.51 min = 89.5 kg. The printed mass implies more.")
    '150 N x 19.51 min = 89.5 kg.'
    >>> first_sentence("Eq. (19) with m0 = 524.895 kg: 18.854 min")
    'Eq. (19) with m0 = 524.895 kg: 18.854 min.'
    """
    first = _SENTENCE_END.split(text.strip(), maxsplit=1)[0].rstrip()
    return first if first.endswith(".") else first + "."
