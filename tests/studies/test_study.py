"""Tests of the engine trade study: parameters, resume, failures, the analytic estimate.

The resume and failure tests run the real Dask machinery (a threaded LocalCluster) with a
stub per-engine task, so they take seconds; the end-to-end CLI run on a two-engine
two-body grid is marked slow.
"""

import math
import subprocess
import sys
from pathlib import Path

import numpy as np
import pandas as pd
import pytest
from scipy.integrate import solve_ivp

from lunarcap.errors import InputError, SolveError
from lunarcap.mission.scenario import paper_scenario
from lunarcap.physics import constants as C
from lunarcap.physics import losses as fbt
from lunarcap.physics.rocket import burn_duration_estimate_s
from lunarcap.studies import campaign
from lunarcap.studies.engine_trade import trade as study

ROOT = Path(__file__).resolve().parents[2]

# ------------------------------------------------------------------ a stub engine task
CALLS = []


def _fake_summary(thrust_N, isp_s, loi):
    imp = study_imp(loi)
    loss = imp * 400.0 / thrust_N ** 2  # any smooth decreasing loss will do
    eq19 = 60.0 / thrust_N
    return {"start_min": -eq19 / 2, "burn_duration_min": 1.01 * eq19, "eq19_duration_min": eq19,
            "delta_v_mps": imp + loss, "impulsive_limit_mps": imp, "objective_loss_mps": loss,
            "objective_loss_percent": 100 * loss / imp, "delta_v_loss_mps": loss,
            "delta_v_loss_percent": 100 * loss / imp, "impulsive_verified": True,
            "m_start_kg": 500.0 - loi, "m_end_kg": 450.0 - loi,
            "fuel_kg": 50.0, "ipopt_status": "Solve_Succeeded", "ipopt_iterations": 9,
            "mesh": "8x16 LGR-5", "solve_wall_s": 0.1, "verification": {"passed": True}}


def study_imp(loi):
    from lunarcap.paper.printed import PAPER_IMPULSIVE_DV_MPS

    return PAPER_IMPULSIVE_DV_MPS[loi - 1]


def fake_engine(thrust_N, isp_s, dynamics):
    CALLS.append((thrust_N, isp_s, dynamics))
    return study.engine_rows(thrust_N, isp_s, dynamics,
                             [_fake_summary(thrust_N, isp_s, n) for n in (1, 2, 3)])


def exploding_engine(thrust_N, isp_s, dynamics):
    if thrust_N == 200.0:
        CALLS.append((thrust_N, isp_s, dynamics))
        raise RuntimeError("worker blew up")
    return fake_engine(thrust_N, isp_s, dynamics)


@pytest.fixture(autouse=True)
def _reset_calls():
    CALLS.clear()
    yield
    CALLS.clear()


def _run(spec, out, task=fake_engine, **kw):
    return study.run_study(spec, out=out, workers=1, progress=False, task=task,
                           processes=False, **kw)


SMALL = study.StudySpec(100.0, 400.0, 3, (250.0, 300.0), "two-body")


# ------------------------------------------------------------------ definitions
def test_thrust_to_weight_is_thrust_over_arrival_mass_times_g0():
    assert study.thrust_to_weight(150.0) == pytest.approx(150.0 / (524.895 * 9.80665), rel=1e-12)
    assert [round(study.thrust_to_weight(t), 4) for t in (150, 300, 450)] == \
        [0.0291, 0.0583, 0.0874]
    # the lunar-weight ratio is larger by g0 / g_moon, g_moon = mu / R^2 = 1.6227 m/s^2
    assert study.G_MOON_MPS2 == pytest.approx(1.6227, abs=1e-4)
    ratio = study.thrust_to_weight(1.0, g_mps2=study.G_MOON_MPS2) / study.thrust_to_weight(1.0)
    assert ratio == pytest.approx(C.G0_MPS2 / study.G_MOON_MPS2)
    assert study.thrust_from_weight_ratio(study.thrust_to_weight(777.0)) == pytest.approx(777.0)
    rows = study.engine_rows(150.0, 200.0, "full", [_fake_summary(150.0, 200.0, n)
                                                    for n in (1, 2, 3)])
    assert {r["thrust_to_weight"] for r in rows} == {study.thrust_to_weight(150.0)}


def test_default_grid_is_30_log_spaced_thrusts_with_exact_endpoints():
    spec = study.StudySpec()
    t = np.array(spec.thrusts_N)
    assert len(t) == 30 and t[0] == 50.0 and t[-1] == 2000.0
    # 4 significant digits kept: each log(t) moves by at most 5e-4
    assert np.allclose(np.diff(np.log(t)), np.log(40.0) / 29, rtol=0, atol=1e-3)
    assert spec.isp_s == (200.0, 250.0, 300.0) and len(spec.engines) == 90


# ------------------------------------------------------------------ validation
@pytest.mark.parametrize("kw, match", [
    ({"points": 1}, "--points: must be an integer >= 2"),
    ({"points": 0}, "--points: must be an integer >= 2"),
    ({"points": 2.5}, "integer"),
    ({"points": "many"}, "integer"),
    ({"points": True}, "integer"),
    ({"thrust_min_N": 0}, "positive"),
    ({"thrust_min_N": -50}, "positive"),
    ({"thrust_min_N": float("nan")}, "--thrust-min: must be a finite number"),
    ({"thrust_max_N": float("inf")}, "--thrust-max: must be a finite number"),
    ({"thrust_max_N": "lots"}, "--thrust-max: must be a number of N"),
    ({"thrust_min_N": 500, "thrust_max_N": 100}, "above the maximum"),
    ({"thrust_min_N": 100, "thrust_max_N": 100}, "empty"),
    ({"thrust_min_N": 100, "thrust_max_N": 100.01, "points": 50}, "not distinct"),
    ({"isp_s": ()}, "empty"),
    ({"isp_s": ""}, "--isp: must be numbers of s separated by commas"),
    ({"isp_s": "200,,300"}, "--isp: must be numbers of s separated by commas"),
    ({"isp_s": "200;300"}, "--isp: must be a number of s"),
    ({"isp_s": [250, 250]}, "duplicates"),
    ({"isp_s": [0]}, "positive"),
    ({"isp_s": None}, "list of numbers"),
    ({"dynamics": "n-body"}, "dynamics"),
])
def test_bad_parameters_give_one_clear_error(kw, match):
    with pytest.raises(InputError, match=match):
        study.StudySpec(**kw)


def test_isp_list_forms():
    assert study.parse_isp_list("200, 250,300") == (200.0, 250.0, 300.0)
    assert study.parse_isp_list([300]) == (300.0,)
    assert study.parse_isp_list(275) == (275.0,)


@pytest.mark.parametrize("kw, match", [
    ({"workers": 0}, "--workers: must be an integer >= 1"),
    ({"workers": "two"}, "integer"),
    ({"scheduler": "  "}, "scheduler"),
])
def test_bad_run_options_fail_before_any_work(tmp_path, monkeypatch, kw, match):
    def no_cluster(*a, **k):
        raise AssertionError("a cluster was started")

    monkeypatch.setattr(campaign, "dask_client", no_cluster)
    opts = {"workers": 1, **kw}
    with pytest.raises(InputError, match=match):
        study.run_study(SMALL, out=tmp_path / "t.csv", progress=False, task=fake_engine, **opts)
    assert not CALLS and not (tmp_path / "t.csv").exists()


def test_unusable_table_paths_fail_before_any_work(tmp_path, monkeypatch):
    monkeypatch.setattr(campaign, "dask_client", lambda *a, **k: pytest.fail("cluster started"))
    with pytest.raises(InputError, match="directory"):
        _run(SMALL, tmp_path)
    other = tmp_path / "other.csv"
    other.write_text("a,b\n1,2\n")
    with pytest.raises(InputError, match="not a study table"):
        _run(SMALL, other)
    assert other.read_text() == "a,b\n1,2\n"  # left alone
    assert not CALLS


def test_cli_bad_parameters_exit_2_with_one_error_line():
    for args in (["--points", "1"], ["--thrust-min", "0"], ["--isp", "200,,300"],
                 ["--thrust-min", "300", "--thrust-max", "100"], ["--workers", "0"]):
        res = subprocess.run([sys.executable, "-m", "lunarcap", "study", *args], cwd=ROOT,
                             capture_output=True, text=True, timeout=60)
        assert res.returncode == 2, (args, res.stderr)
        lines = [ln for ln in res.stderr.splitlines() if "error:" in ln]
        assert len(lines) == 1 and lines[0].startswith("lunarcap: error: "), res.stderr
        assert "Traceback" not in res.stderr and res.stdout == ""


# ------------------------------------------------------------------ resume
def test_study_writes_four_rows_per_engine_and_a_run_record(tmp_path):
    out = tmp_path / "t.csv"
    res = _run(SMALL, out)
    assert sorted(CALLS) == sorted((t, i, "two-body") for t, i in SMALL.engines)
    table = study.read_table(out)
    assert len(table) == 4 * 6 and list(table.columns) == list(study.COLUMNS)
    assert set(table.part) == set(study.PARTS) and set(table.status) == {"ok"}
    assert len(res.table) == 24 and res.failures.empty
    wide = res.wide()
    assert len(wide) == 6 and (wide.status == "ok").all()
    seq = res.table[res.table.part == "sequence"]
    per_loi = res.table[res.table.part != "sequence"].groupby(["thrust_N",
                                                               "isp_s"]).objective_loss_mps.sum()
    assert np.allclose(seq.set_index(["thrust_N", "isp_s"]).objective_loss_mps.sort_index(),
                       per_loi.sort_index())
    runs = study.read_runs(out)
    assert len(runs) == 1 and runs[0]["computed"] == 6 and runs[0]["reused"] == 0
    assert runs[0]["wall_s"] > 0


def test_rerun_computes_nothing(tmp_path):
    out = tmp_path / "t.csv"
    _run(SMALL, out)
    text = out.read_text()
    CALLS.clear()
    res = _run(SMALL, out)
    assert CALLS == [] and out.read_text() == text
    assert res.run["computed"] == 0 and res.run["reused"] == 6 and len(res.table) == 24
    assert len(study.read_runs(out)) == 2


def test_interrupted_table_is_completed_not_recomputed(tmp_path):
    out = tmp_path / "t.csv"
    _run(SMALL, out)
    lines = out.read_text().splitlines(keepends=True)
    partial = "".join(lines[:1 + 4 * 2])  # header and the first two engines
    out.write_text(partial)
    done = {(r.thrust_N, r.isp_s) for r in study.read_table(out).itertuples()}
    CALLS.clear()
    res = _run(SMALL, out)
    assert len(CALLS) == 4
    assert not done & {(t, i) for t, i, _ in CALLS}
    assert out.read_text().startswith(partial)  # finished rows untouched
    assert len(study.read_table(out)) == 24 and len(res.table) == 24
    assert res.run["computed"] == 4 and res.run["reused"] == 2


def test_interrupt_keeps_finished_engines_and_logs_the_run(tmp_path, monkeypatch):
    out = tmp_path / "t.csv"
    real = campaign._compute

    def compute_then_ctrl_c(client, task, todo, *args):
        real(client, task, todo[:2], *args)  # two engines finish, then Ctrl-C
        raise KeyboardInterrupt

    monkeypatch.setattr(campaign, "_compute", compute_then_ctrl_c)
    with pytest.raises(KeyboardInterrupt):
        _run(SMALL, out)
    assert len(study.read_table(out)) == 8
    run = study.read_runs(out)[-1]
    assert run["interrupted"] and run["computed"] == 2
    monkeypatch.setattr(campaign, "_compute", real)
    CALLS.clear()
    res = _run(SMALL, out)
    assert len(CALLS) == 4 and res.run["reused"] == 2 and not res.run["interrupted"]


def test_a_table_without_trailing_newline_is_appended_cleanly(tmp_path):
    out = tmp_path / "t.csv"
    _run(SMALL, out)
    lines = out.read_text().splitlines()
    out.write_text("\n".join(lines[:1 + 4]))  # one engine, no final newline
    CALLS.clear()
    _run(SMALL, out)
    assert len(CALLS) == 5 and len(study.read_table(out)) == 24


def test_overlapping_grid_reuses_shared_engines(tmp_path):
    out = tmp_path / "t.csv"
    _run(study.StudySpec(100.0, 400.0, 2, (250.0,), "two-body"), out)  # 100 and 400 N
    CALLS.clear()
    res = _run(study.StudySpec(100.0, 400.0, 3, (250.0,), "two-body"), out)  # adds 200 N
    assert [c[0] for c in CALLS] == [200.0]
    assert sorted(res.table.thrust_N.unique()) == [100.0, 200.0, 400.0]
    CALLS.clear()
    _run(study.StudySpec(100.0, 400.0, 2, (250.0,), "full"), out)  # other dynamics: new
    assert len(CALLS) == 2


def test_rows_of_another_code_version_are_not_reused(tmp_path, monkeypatch):
    out = tmp_path / "t.csv"
    _run(SMALL, out)
    import lunarcap.repro.cache

    monkeypatch.setattr(lunarcap.repro.cache, "code_version", lambda *a, **k: "0123456789abcdef")
    CALLS.clear()
    res = _run(SMALL, out)
    assert len(CALLS) == 6 and set(res.table.code_version) == {"0123456789abcdef"}
    assert len(study.read_table(out)) == 48  # the old rows are kept, not used


def test_failed_task_is_recorded_and_not_retried_unless_asked(tmp_path):
    out = tmp_path / "t.csv"
    spec = study.StudySpec(100.0, 400.0, 3, (250.0,), "two-body")
    res = _run(spec, out, task=exploding_engine)
    bad = res.table[res.table.thrust_N == 200.0].set_index("part")
    assert list(bad.loc[["LOI1", "LOI2", "LOI3"], "status"]) == ["task error"] * 3
    assert bad.loc["sequence", "status"] == "incomplete"
    assert "worker blew up" in bad.loc["LOI1", "error"]
    assert len(res.failures) == 3 and res.run["failed_computed"] == 1
    CALLS.clear()
    _run(spec, out, task=exploding_engine)
    assert CALLS == []  # recorded failures are not retried forever
    _run(spec, out, task=fake_engine, retry_failed=True)
    assert [c[0] for c in CALLS] == [200.0]
    res = _run(spec, out)
    assert res.failures.empty and len(res.table) == 12  # the latest rows win


def test_solve_error_in_the_chain_is_recorded_with_ipopt_status(monkeypatch):
    import lunarcap.capture.chain as sequence

    class FakeSolution:
        def __init__(self, s):
            self._s = s

        def summary(self):
            return self._s

    def fake_solve_burn(key):
        loi = key.n_burns
        assert all(b.free_start for b in key.burns)  # the free-ignition chain
        if loi == 2:
            raise SolveError("LOI 2 failed on every mesh", status="Maximum_Iterations_Exceeded")
        s = _fake_summary(key.engine.thrust_N, key.engine.isp_s, loi)
        s["objective_j_mps"] = s["delta_v_mps"] + 2000.0
        return FakeSolution(s)

    def fake_impulsive_limit(key):
        imp = study_imp(key.n_burns)
        return {"delta_v_mps": imp, "objective_j_mps": imp + 2000.0, "verification_passed": True}

    monkeypatch.setattr(sequence, "solve_burn", fake_solve_burn)
    monkeypatch.setattr(sequence, "impulsive_limit", fake_impulsive_limit)
    rows = {r["part"]: r for r in study.solve_engine(300.0, 250.0, "full")}
    assert rows["LOI1"]["status"] == "ok"
    assert rows["LOI2"]["status"] == "failed"
    assert rows["LOI2"]["ipopt_status"] == "Maximum_Iterations_Exceeded"
    assert rows["LOI3"]["status"] == "not run" and "LOI 2" in rows["LOI3"]["error"]
    assert rows["sequence"]["status"] == "incomplete"
    assert "Maximum_Iterations_Exceeded" in rows["sequence"]["error"]
    assert math.isnan(rows["sequence"]["objective_loss_mps"])
    assert rows["sequence"]["analytic_loss_mps"] > 0  # closed form, always there


def test_a_table_in_use_is_refused(tmp_path):
    out = tmp_path / "t.csv"
    with campaign.table_lock(out):
        with pytest.raises(InputError, match="another run"):
            _run(SMALL, out)
    assert not CALLS


# ------------------------------------------------------------------ analytic estimate
def test_robbins_formula_value_and_burn_time_squared_scaling():
    w = fbt.schuler_rate_rad_s(C.R_MOON + 100.0)
    assert w == pytest.approx(math.sqrt(C.MU_MOON / (C.R_MOON + 100.0) ** 3))
    r = C.R_MOON + 100.0   # the paper's perilune radius, km
    assert fbt.robbins_loss_mps(240.0, 1.0 / w, r) == pytest.approx(10.0)
    base = fbt.robbins_loss_mps(300.0, 600.0, r)
    assert fbt.robbins_loss_mps(300.0, 1200.0, r) == pytest.approx(4 * base)
    assert fbt.robbins_loss_mps(600.0, 600.0, r) == pytest.approx(2 * base)
    assert fbt.robbins_loss_mps(300.0, 0.0, r) == 0.0
    with pytest.raises(InputError):
        fbt.robbins_loss_mps(300.0, -1.0, r)


def test_analytic_loss_vanishes_as_thrust_grows_like_one_over_thrust_squared():
    loss = [sum(r["analytic_loss_mps"] for r in study.capture_chain_estimate(t, 250.0))
            for t in (1e2, 1e3, 1e4, 1e5)]
    assert all(a > b for a, b in zip(loss, loss[1:]))
    assert loss[-1] < 1e-4
    # Eq. (19): t_b ~ 1/T exactly, so the estimate falls by 100 per decade of thrust
    assert np.allclose(np.array(loss[:-1]) / np.array(loss[1:]), 100.0, rtol=1e-9)


def test_chain_estimate_uses_eq19_with_the_impulsive_chain_masses():
    est = study.capture_chain_estimate(150.0, 200.0)
    m = paper_scenario().mass_kg
    for e in est:
        assert e["m_before_kg"] == pytest.approx(m)
        tb = burn_duration_estimate_s(m, e["paper_impulsive_delta_v_mps"], 150.0, 200.0)
        assert e["eq19_duration_min"] == pytest.approx(tb / 60.0)
        m *= math.exp(-e["paper_impulsive_delta_v_mps"] / (C.G0_MPS2 * 200.0))


def _fixed_direction_burn_loss(r_km, v_kmps, dv_mps, omega_tb):
    """Energy-equivalent loss (m/s) of a constant-acceleration, inertially fixed burn
    centred on an apse (planar two-body), against the tangential impulse at the apse."""
    mu = C.MU_MOON
    w = math.sqrt(mu / r_km ** 3)
    tb = omega_tb / w
    acc = dv_mps * 1e-3 / tb  # km/s^2 along +y, the velocity direction at the apse

    def f(t, s, a):
        x, y, vx, vy = s
        r3 = (x * x + y * y) ** 1.5
        return [vx, vy, -mu * x / r3, -mu * y / r3 + a]

    opts = dict(method="DOP853", rtol=1e-13, atol=1e-15)
    back = solve_ivp(f, (0.0, -tb / 2), [r_km, 0.0, 0.0, v_kmps], args=(0.0,), **opts)
    burn = solve_ivp(f, (-tb / 2, tb / 2), back.y[:, -1], args=(acc,), **opts)
    x, y, vx, vy = burn.y[:, -1]
    e_fin = 0.5 * (vx * vx + vy * vy) - mu / math.hypot(x, y)
    e_imp = 0.5 * (v_kmps + dv_mps * 1e-3) ** 2 - mu / r_km
    return (e_imp - e_fin) / v_kmps * 1e3


@pytest.mark.parametrize("orbit", ["circular", "12 h ellipse perilune"])
@pytest.mark.parametrize("omega_tb", [0.1, 0.3])
def test_robbins_is_the_leading_order_loss_of_a_fixed_direction_burn(orbit, omega_tb):
    # the limit the formula must reach: dV << v, omega t_b << 1, constant acceleration in
    # a fixed inertial direction, centred on an apse
    r = C.R_MOON + 100.0   # the paper's perilune radius, km
    if orbit == "circular":
        v = math.sqrt(C.MU_MOON / r)
    else:
        a = (C.MU_MOON * (paper_scenario().capture_periods_s[0] / (2 * math.pi)) ** 2) ** (1 / 3)
        v = math.sqrt(C.MU_MOON * (2 / r - 1 / a))
    dv = 0.5  # m/s
    loss = _fixed_direction_burn_loss(r, v, dv, omega_tb)
    expected = fbt.robbins_loss_mps(dv, omega_tb / fbt.schuler_rate_rad_s(r), r)
    assert loss == pytest.approx(expected, rel=1e-3 + omega_tb ** 2 / 10)


# ------------------------------------------------------------------ paper and curves
def test_paper_points_are_table_b1():
    p = study.paper_points().set_index(["thrust_N", "part"])
    assert p.loc[(150.0, "LOI1"), "paper_delta_v_loss_percent"] == 3.93
    assert p.loc[(450.0, "LOI3"), "paper_delta_v_loss_percent"] == 0.22
    seq = (367.415 + 257.527 + 248.000) - (353.272 + 254.034 + 245.363)
    assert p.loc[(150.0, "sequence"), "paper_delta_v_loss_mps"] == pytest.approx(seq)
    assert p.loc[(150.0, "sequence"),
                 "paper_delta_v_loss_percent"] == pytest.approx(100 * seq / 852.669)
    assert p.loc[(300.0, "LOI1"), "isp_s"] == 250.0


def test_analytic_curves_match_the_chain_estimate():
    df = study.analytic_curves([150.0, 300.0], [200.0])
    assert len(df) == 8 and set(df.part) == set(study.PARTS)
    est = study.capture_chain_estimate(150.0, 200.0)
    row = df[(df.thrust_N == 150.0) & (df.part == "sequence")].iloc[0]
    assert row.analytic_loss_mps == pytest.approx(sum(e["analytic_loss_mps"] for e in est))


# ------------------------------------------------------------------ end to end
@pytest.mark.slow
def test_cli_small_two_body_study_and_resume(tmp_path):
    out = tmp_path / "study.csv"
    args = [sys.executable, "-m", "lunarcap", "study", "--thrust-min", "1000", "--thrust-max",
            "2000", "--points", "2", "--isp", "300", "--dynamics", "two-body", "--workers", "1",
            "--out", str(out), "--no-progress"]
    res = subprocess.run(args, cwd=ROOT, capture_output=True, text=True, timeout=600)
    assert res.returncode == 0, res.stdout + res.stderr
    assert "2 engine(s) computed, 0 taken from the table, 0 failed" in res.stdout
    table = pd.read_csv(out)
    assert len(table) == 8 and set(table.status) == {"ok"}
    loi = table[table.part != "sequence"]
    assert (loi.burn_duration_min / loi.eq19_duration_min).between(0.95, 1.05).all()
    assert (table.objective_loss_percent.abs() < 0.2).all()  # strong engines: near-impulsive
    res = subprocess.run(args, cwd=ROOT, capture_output=True, text=True, timeout=120)
    assert res.returncode == 0 and "0 engine(s) computed, 2 taken from the table" in res.stdout


@pytest.mark.slow
def test_strong_engine_loses_little_and_never_more_than_robbins():
    """The study's loss is measured against the impulsive limit in the same dynamics.

    Two-body, 2000 N / 300 s (T/W 0.39): every burn's loss is positive (an impulse from the
    same orbit does at least as well) and equals Robbins' closed-form leading term within
    1 % (omega_s t_b <= 0.08 here, deep inside its expansion, where optimal steering gains
    only at higher order) without exceeding it; for LOI 3, whose circle fixes the end speed,
    the objective loss is the delta-V loss.
    Against the paper's impulsive values LOI 2 would instead read 0.12 m/s too high (the
    two-body LOI 2 impulse is 253.911 m/s, the paper prints 254.034): a model offset.
    """
    rows = {r["part"]: r for r in study.solve_engine(2000.0, 300.0, "two-body")}
    assert all(r["status"] == "ok" and r["verified"] for r in rows.values())
    for part in ("LOI1", "LOI2", "LOI3"):
        r = rows[part]
        ratio = r["objective_loss_mps"] / r["analytic_loss_mps"]
        assert 0.99 < ratio <= 1.0 + 1e-6, (part, r["objective_loss_mps"], r["analytic_loss_mps"])
        assert r["impulsive_limit_mps"] == pytest.approx(
            {"LOI1": 353.272, "LOI2": 253.911, "LOI3": 245.178}[part], abs=2e-3)
    assert rows["LOI3"]["objective_loss_mps"] == pytest.approx(rows["LOI3"]["delta_v_loss_mps"],
                                                               abs=1e-6)
    seq = rows["sequence"]
    assert seq["objective_loss_mps"] == pytest.approx(
        sum(rows[p]["objective_loss_mps"] for p in ("LOI1", "LOI2", "LOI3")))
    assert 0.99 * seq["analytic_loss_mps"] < seq["objective_loss_mps"] <= seq["analytic_loss_mps"]
