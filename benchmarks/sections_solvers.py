"""Work-precision sections: the toolkit's integrators against compiled peers at equal error.

* ``springblock`` — one period of the Fig. 3 stick-slip cycle of Putelat, Dawes & Willis (2010)
  (Dieterich law, V/V_* = 100, κ = 1e-3): ``integrate`` with its default method (the one every
  command, check and figure uses; read from its signature at run time) against ``solve_ivp``
  Radau/BDF/LSODA with the generated right-hand side and Jacobian compiled, ``solve_ivp`` Radau
  with them as plain Python, SUNDIALS CVODE (scikit-sundae) and, where installed, numbalsoda.
* ``forced`` — Skurativskyi et al. (2019) eq. (1) at ω = 16 (20 periods) and ω = 15 (2 periods):
  the toolkit with its impact log against CVODE and LSODA (compiled, without events) and
  ``solve_ivp`` DOP853 with the contact event.
* ``galvanetto`` — Galvanetto (2004) one block (slip→stick event time) and two blocks (one step
  of the event map): the hybrid engine against ``solve_ivp`` loops with terminal events.

Every peer runs down its own tolerance ladder until it reaches the smallest error the toolkit
reaches (or fails, or one run exceeds a CPU budget), and ratios are read along both Pareto
fronts only at errors both sides reach.
"""

from __future__ import annotations

import inspect

import numpy as np
from benchlib import RAW, TABLES, Goal, cpu_time, ladder, plot_work_precision, ratios_at_equal_error, report, table


def _results():
    import benchlib

    return benchlib.RESULTS


def default_method(fn) -> str | None:
    """The default of ``fn``'s ``method`` keyword (None when it takes none)."""
    p = inspect.signature(fn).parameters.get("method")
    return None if p is None or p.default is inspect.Parameter.empty else str(p.default)


# --------------------------------------------------------------------------------------------
# spring-block (goal 2)
def section_springblock(quick: bool) -> None:
    from scipy.integrate import solve_ivp

    from landau.verify.springblock.simulate import W_INDEX, integrate
    from landau.verify.springblock.workprecision import error, fig3_cycle, fig3_model, scipy_run

    model = fig3_model()
    orbit = fig3_cycle(model)
    y0 = np.insert(orbit.z, W_INDEX, 0.0)
    T = orbit.period
    c, p, n = model.compiled, model.p, model.n
    Ts = T / model.time_unit
    ref = integrate(model, y0, (0.0, T), rtol=1e-13).y_final
    rows = []
    meth = default_method(integrate)
    ours = f"landau integrate (default{', ' + meth if meth else ''})"
    for rtol in [10.0 ** -e for e in range(4, 12 if quick else 13)]:
        y, cpu = cpu_time(lambda: integrate(model, y0, (0.0, T), rtol=rtol).y_final)
        rows.append({"method": ours, "rtol": rtol, "error": error(y, ref), "cpu": cpu})
    floor = min(r["error"] for r in rows)

    def f_c(t, y):
        out = np.empty(n)
        c.rhs(t, y, p, out)
        return out

    def j_c(t, y):
        out = np.empty((n, n))
        c.jac(t, y, p, out)
        return out

    peers = {}
    for m in ("Radau", "BDF", "LSODA"):
        def run(rtol, m=m):
            s = solve_ivp(f_c, (0.0, Ts), y0, method=m, rtol=rtol, atol=rtol, jac=j_c)
            if not s.success:
                raise RuntimeError(s.message)
            return s.y[:, -1]
        # scipy steps in Python whatever f and J are: these are Python steppers, never "compiled peers"
        peers[f"solve_ivp {m} (Python stepper, compiled f+J)"] = (run, 1)
    def python_radau(rtol):
        return scipy_run(model, y0, T, "Radau", rtol, True)[0]
    peers["solve_ivp Radau (Python stepper, Python f+J)"] = (python_radau, 1)
    try:
        from sksundae.cvode import CVODE

        def rhs_s(t, y, yp):
            c.rhs(t, np.array(y), p, yp)

        def jac_s(t, y, yp, JJ):
            out = np.empty((n, n))
            c.jac(t, np.array(y), p, out)
            JJ[:, :] = out

        def cvode(rtol):
            s = CVODE(rhs_s, jacfn=jac_s, rtol=rtol, atol=rtol, max_num_steps=10 ** 7).solve([0.0, Ts], y0)
            if not s.success:
                raise RuntimeError(s.message)
            return s.y[-1]

        peers["CVODE BDF (compiled stepper, compiled f+J called through Python)"] = (cvode, 3)
    except ImportError:
        print("  (scikit-sundae not installed: pip install -e '.[bench]')")
    try:
        import numba as nb
        from numbalsoda import lsoda, lsoda_sig

        rhs_nb = c.rhs

        @nb.cfunc(lsoda_sig)
        def rhs_l(t, u, du, pp):
            rhs_nb(t, nb.carray(u, (n,)), nb.carray(pp, (p.size,)), nb.carray(du, (n,)))

        addr = rhs_l.address

        def lsoda_run(rtol):
            usol, ok = lsoda(addr, y0.copy(), np.array([0.0, Ts]), data=p.copy(), rtol=rtol, atol=rtol,
                             mxstep=10 ** 7)
            if not ok:
                raise RuntimeError("lsoda failed")
            return usol[-1]

        peers["numbalsoda LSODA (compiled stepper, compiled f)"] = (lsoda_run, 3)
    except ImportError:
        print("  (numbalsoda not installed: it builds from source with a Fortran compiler)")
    # the peers' ladders start where their errors are comparable and go on until they reach the
    # toolkit's smallest error (multistep methods need tolerances ~1e4 tighter on this cycle)
    for name, (fn, repeat) in peers.items():
        start = 4 if "Python f+J" in name else 5
        def one(rtol, fn=fn, repeat=repeat):
            y, cpu = cpu_time(lambda: fn(rtol), repeat=repeat)
            return error(y, ref), cpu
        for rt, err, cpu, note in ladder(one, [10.0 ** -e for e in range(start, 16)], floor,
                                         budget=5.0 if quick else 30.0):
            rows.append({"method": name, "rtol": rt, "error": err, "cpu": cpu, "note": note})
    compiled = [m for m in peers if "compiled stepper" in m]
    RAW["springblock"] = rows
    TABLES["springblock"] = (f"One period T = {T:.6g} s of the Fig. 3 cycle (Putelat et al. 2010), error at the end "
                             f"against the toolkit at rtol 1e-13 (max scaled state error); the toolkit is "
                             f"`integrate` with its default method{' (' + meth + ')' if meth else ''}.\n\n"
                             + table(rows, ["method", "rtol", "error", "cpu", "note"]))
    plot_work_precision(rows, "Spring-block, one period of the Fig. 3 stick-slip cycle (Dieterich)",
                        _results() / "springblock.png", "error at the end of one period")
    targets = [1e-4, 1e-5, 1e-6, 1e-7, 1e-8, 1e-9, 1e-10]
    for tgt, (theirs, mine, who) in ratios_at_equal_error(rows, ours, compiled, targets).items():
        report(Goal("springblock", "2", f"spring-block: best compiled peer / toolkit CPU at error {tgt:.0e}",
                    theirs / mine, 3.0, note=f"best peer: {who}"))
    for tgt, (theirs, mine, _) in ratios_at_equal_error(rows, ours, ["solve_ivp Radau (Python stepper, Python f+J)"],
                                                        [1e-6, 1e-8]).items():
        report(Goal("springblock", "2", f"spring-block: scipy Radau (Python f+J) / toolkit at error {tgt:.0e}",
                    theirs / mine, 50.0))


# --------------------------------------------------------------------------------------------
# forced oscillator (goal 3)
def section_forced(quick: bool) -> None:
    from landau.verify.benchmarks.skurativskyi_work_precision import errors, scipy_run, toolkit_run
    from landau.verify.skurativskyi.model import Params, accel
    from landau.verify.skurativskyi.simulate import rest_state, run

    run(Params(), 1)  # compile
    cases = [(16.0, 20), (15.0, 2)]
    rows = []
    ours = "landau (with impact log)"
    for omega, nper in cases:
        prm = Params(omega=omega)
        pk = prm.packed()
        tend = nper * prm.period
        ref, _, _ = toolkit_run(prm, nper, 1e-12, repeat=1, min_cpu=0)
        yref = ref[0]

        def state_error(y, yref=yref):
            return float(np.max(np.abs((np.asarray(y) - yref) / np.array([1e-3, 1e-2]))))

        mine = []
        for rt in (1e-5, 1e-6, 1e-7, 1e-8, 1e-9, 1e-10):
            res, cpu, _ = toolkit_run(prm, nper, rt, repeat=3)
            mine.append({"omega": omega, "method": ours, "rtol": rt, "error": errors(res, ref)[0], "cpu": cpu})
        rows += mine
        floor = min(r["error"] for r in mine)
        peers = {}
        try:
            from sksundae.cvode import CVODE

            def make_rhs(pk):  # CVODE reads a fourth parameter as user data: bind pk by closure
                def rhs_s(t, y, yp):
                    yp[0] = y[1]
                    yp[1] = accel(t, y[0], y[1], pk)
                return rhs_s
            rhs_s = make_rhs(pk)

            for meth in ("Adams", "BDF"):
                def cv(rt, meth=meth, prm=prm, tend=tend, rhs_s=rhs_s):
                    # max_step: started from rest, the forcing is invisible to CVODE's first error
                    # tests, and without a cap it steps over all 20 periods in four steps
                    s = CVODE(rhs_s, method=meth, rtol=rt, atol=[rt * 1e-4, rt * 1e-2],
                              max_step=prm.period / 20, max_num_steps=5_000_000).solve([0.0, tend], rest_state(prm))
                    if not s.success:
                        raise RuntimeError(s.message)
                    return s.y[-1]
                peers[f"CVODE {meth} (no events)"] = (cv, 1)
        except ImportError:
            pass
        try:
            import numba as nb
            from numbalsoda import lsoda, lsoda_sig

            npk = pk.size
            # numbalsoda takes one scalar atol: integrate (x/1e-4 m, ẋ/1e-2 m/s), which is the
            # same as the per-component atol (rtol·1e-4 m, rtol·1e-2 m/s) of the other runs
            s0, s1 = 1e-4, 1e-2

            @nb.cfunc(lsoda_sig)
            def rhs_l(t, u, du, pp):
                uu = nb.carray(u, (2,))
                dd = nb.carray(du, (2,))
                dd[0] = uu[1] * s1 / s0
                dd[1] = accel(t, uu[0] * s0, uu[1] * s1, nb.carray(pp, (npk,))) / s1

            def ls(rt, prm=prm, tend=tend, pk=pk, addr=rhs_l.address):
                u0 = rest_state(prm) / np.array([s0, s1])
                usol, ok = lsoda(addr, u0, np.array([0.0, tend]), data=pk.copy(), rtol=rt, atol=rt, mxstep=10 ** 8)
                if not ok:
                    raise RuntimeError("lsoda failed")
                return usol[-1] * np.array([s0, s1])
            peers["numbalsoda LSODA (no events)"] = (ls, 3)
        except ImportError:
            pass
        for name, (fn, repeat) in peers.items():
            def one(rt, fn=fn, repeat=repeat):
                y, cpu = cpu_time(lambda: fn(rt), repeat=repeat)
                return state_error(y), cpu
            for rt, err, cpu, note in ladder(one, [10.0 ** -e for e in range(5, 16)], floor,
                                             budget=10.0 if quick else 60.0):
                rows.append({"omega": omega, "method": name, "rtol": rt, "error": err, "cpu": cpu, "note": note})
        for rt in ((1e-5, 1e-6) if quick else (1e-5, 1e-6, 1e-7)):
            res, cpu, _ = scipy_run(prm, nper, "DOP853", rt)
            rows.append({"omega": omega, "method": "solve_ivp DOP853 + event", "rtol": rt,
                         "error": errors(res, ref)[0] if res is not None else float("nan"), "cpu": cpu})
        sub = [r for r in rows if r["omega"] == omega]
        plot_work_precision(sub, f"Skurativskyi et al. (2019) eq. (1), ω = {omega:g}, {nper} periods",
                            _results() / f"forced_omega{omega:g}.png", "scaled final-state error")
        eq = ratios_at_equal_error(sub, ours, list(peers), [1e-4, 1e-5, 1e-6, 1e-7, 1e-8, 1e-9])
        for tgt, (theirs, mine_cpu, who) in eq.items():
            report(Goal("forced", "3", f"forced ω={omega:g}: compiled peer (no events) / toolkit at error {tgt:.0e}",
                        theirs / mine_cpu, 1.0, note=f"best peer: {who}"))
        eq = ratios_at_equal_error(sub, ours, ["solve_ivp DOP853 + event"], [1e-4, 1e-5, 1e-6])
        for tgt, (theirs, mine_cpu, _) in eq.items():
            report(Goal("forced", "3", f"forced ω={omega:g}: solve_ivp + event / toolkit at error {tgt:.0e}",
                        theirs / mine_cpu, 100.0))
    RAW["forced"] = rows
    TABLES["forced"] = ("Skurativskyi et al. (2019) eq. (1) from rest; error = max |Δ(x, ẋ)|/(1 mm, 10 mm/s) at the "
                        "end against the toolkit at rtol 1e-12; each peer's tolerance ladder goes on until it reaches "
                        "the toolkit's smallest error (or fails).\n\n"
                        + table(rows, ["omega", "method", "rtol", "error", "cpu", "note"]))


# --------------------------------------------------------------------------------------------
# Galvanetto blocks (goal 4)
def section_galvanetto(quick: bool) -> None:
    """The engine as the Galvanetto figures run it (its compiled stepper where the module offers
    one) against ``solve_ivp`` loops with terminal events, at equal event-time error."""
    import landau.verify.benchmarks.event_location_galvanetto as ev

    t_ref = ev.engine("DOP853", 1e-13)[0]
    methods = [("hybrid engine DOP853", lambda rtol: ev.engine("DOP853", rtol))]
    if hasattr(ev, "compiled_engine"):
        methods.append(("hybrid engine, compiled stepper", ev.compiled_engine))
    methods += [("solve_ivp DOP853 + terminal event", lambda rtol: ev.baseline("DOP853", rtol)),
                ("solve_ivp RK45 + terminal event", lambda rtol: ev.baseline("RK45", rtol))]
    ours = methods[1][0] if hasattr(ev, "compiled_engine") else methods[0][0]
    rows = _event_rows(methods, t_ref, range(4, 15, 2 if quick else 1))
    RAW["galvanetto"] = rows
    TABLES["galvanetto"] = ("Galvanetto (2004) one block (γ = 3, δ = 0.2, V = 1): slip→stick event time against the "
                            "engine at rtol 1e-13 (atol = rtol/100 throughout).\n\n"
                            + table(rows, ["method", "rtol", "error", "nfev", "cpu", "note"]))
    plot_work_precision(rows, "Galvanetto (2004) one block: slip→stick event time", _results() / "galvanetto.png",
                        "event-time error")
    theirs = ["solve_ivp DOP853 + terminal event", "solve_ivp RK45 + terminal event"]
    for tgt, (their, mine, who) in ratios_at_equal_error(rows, ours, theirs, [1e-5, 1e-7, 1e-9, 1e-11]).items():
        report(Goal("galvanetto", "4", f"Galvanetto: best solve_ivp loop / engine CPU at event-time error {tgt:.0e}",
                    their / mine, 1.0, note=f"{who}; {ours}"))

    t_ref2 = ev.two_block_engine("DOP853", 1e-13)[0]
    methods2 = [("hybrid engine DOP853", lambda rtol: ev.two_block_engine("DOP853", rtol))]
    if hasattr(ev, "two_block_compiled_engine"):
        methods2.append(("hybrid engine, compiled stepper", ev.two_block_compiled_engine))
    methods2.append(("solve_ivp DOP853 loop, terminal events", lambda rtol: ev.two_block_baseline("DOP853", rtol)))
    ours2 = methods2[1][0] if len(methods2) == 3 else methods2[0][0]
    rows2 = _event_rows(methods2, t_ref2, range(5, 14, 2 if quick else 1))
    RAW["galvanetto_two_blocks"] = rows2
    TABLES["galvanetto"] += (
        "\n\nGalvanetto (2004) two blocks (α = 1.2, β = 1.722, γ = 3, V = 0.25): one step of the event map from the "
        "global stick phase d = -0.3 (eight switching events); error = time of the next global stick phase against "
        "the engine at rtol 1e-13.\n\n" + table(rows2, ["method", "rtol", "error", "nfev", "cpu", "note"]))
    plot_work_precision(rows2, "Galvanetto (2004) two blocks: one event-map step",
                        _results() / "galvanetto_two_blocks.png", "error of the time of the next global stick phase")
    eq = ratios_at_equal_error(rows2, ours2, ["solve_ivp DOP853 loop, terminal events"], [1e-6, 1e-8, 1e-10, 1e-12])
    for tgt, (their, mine, _) in eq.items():
        report(Goal("galvanetto", "4", f"Galvanetto two blocks: solve_ivp loop / engine CPU at error {tgt:.0e}",
                    their / mine, 1.0, note=ours2))


def _event_rows(methods, t_ref, exponents):
    rows, dead = [], set()
    for e in exponents:
        rtol = 10.0 ** -e
        for label, fn in methods:
            if label in dead:
                continue
            try:
                (t_ev, *rest), cpu = cpu_time(lambda: fn(rtol), min_time=0.1, repeat=5)
            except Exception as exc:  # a method that fails ends its ladder, reported
                rows.append({"method": label, "rtol": rtol, "error": float("nan"), "nfev": 0, "cpu": float("nan"),
                             "note": type(exc).__name__})
                dead.add(label)
                continue
            err = abs(t_ev - t_ref)
            rows.append({"method": label, "rtol": rtol, "error": err, "nfev": int(rest[-1]), "cpu": cpu, "note": ""})
            if cpu > 5.0:
                dead.add(label)  # off the front the goals read
    return rows
