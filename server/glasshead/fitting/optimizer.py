"""Bounded, derivative-free minimisation over NLopt's local methods.

Cohen, Beskow and Massaro (1998) fitted their tongue to measurements with STEPIT, a
derivative-free direct search. The rig's objectives are the same kind of function: cheap, a few
to a dozen parameters, no gradient, and piecewise smooth (a ray can change the segment it
crosses). NLopt offers three such local methods with bounds:

- ``praxis``: Brent's principal-axis method (LN_PRAXIS), the closest relative of STEPIT's
  conjugate directions; NLopt keeps it inside the bounds by answering +inf outside them;
- ``bobyqa``: Powell's bound-constrained quadratic models (LN_BOBYQA), few evaluations on smooth
  functions;
- ``sbplx``: Rowan's subplex, Nelder-Mead on subspaces (LN_SBPLX), robust on rough functions.

``minimize`` keeps the best point it has seen, so a method that stops on round-off (NLopt raises
``RoundoffLimited``) still returns a result.
"""

import math
import time
from collections.abc import Callable
from dataclasses import dataclass, fields, replace
from typing import TYPE_CHECKING, Any, TypeVar

import nlopt
import numpy as np

if TYPE_CHECKING:
    from _typeshed import DataclassInstance

METHODS = {"praxis": nlopt.LN_PRAXIS, "bobyqa": nlopt.LN_BOBYQA, "sbplx": nlopt.LN_SBPLX}
#: ``progress(evaluations, best_error)``: called after every evaluation of a fit.
Progress = Callable[[int, float], None]
Options = TypeVar("Options", bound="DataclassInstance")

#: NLopt's result codes, as words for reports.
STOP_REASONS = {
    nlopt.SUCCESS: "success",
    nlopt.STOPVAL_REACHED: "stopval reached",
    nlopt.FTOL_REACHED: "ftol reached",
    nlopt.XTOL_REACHED: "xtol reached",
    nlopt.MAXEVAL_REACHED: "max evaluations reached",
    nlopt.MAXTIME_REACHED: "max time reached",
}


@dataclass
class OptimizeResult:
    """x: best parameters (n,); error: the objective there; evaluations: objective calls;
    seconds: wall time; method: the method's name; stop: why it stopped."""

    x: np.ndarray
    error: float
    evaluations: int
    seconds: float
    method: str
    stop: str


def minimize(objective: Callable[[np.ndarray], float], x0, lower, upper, *,
             method: str = "bobyqa", max_evals: int = 2000, xtol_rel: float = 1e-6,
             xtol_abs: float = 1e-6, ftol_abs: float = 1e-10, ftol_rel: float = 0.0,
             max_seconds: float = 0.0, stopval: float | None = None,
             initial_step=None,
             progress: Callable[[int, float], None] | None = None) -> OptimizeResult:
    """Minimise ``objective(x) -> float`` from x0 within [lower, upper] with a local NLopt method.

    xtol_abs matters as well as xtol_rel: the rig's neutral values are 0, where a relative step
    test alone never passes. ``initial_step`` (scalar or (n,)) defaults to a tenth of each range.
    ``progress(evaluations, best_error)``, when given, is called after every evaluation (for a
    job's progress bar); it must be cheap, and an exception it raises stops the fit.
    Raises ValueError for an unknown method, mismatched shapes, empty or inverted bounds or an x0
    outside them.
    """
    if method not in METHODS:
        raise ValueError(f"unknown method {method!r}; choose one of: {', '.join(METHODS)}")
    x0 = np.asarray(x0, dtype=np.float64).ravel()
    lower = np.asarray(lower, dtype=np.float64).ravel()
    upper = np.asarray(upper, dtype=np.float64).ravel()
    if x0.size == 0 or lower.shape != x0.shape or upper.shape != x0.shape:
        raise ValueError(f"x0, lower and upper must have the same non-empty shape; got "
                         f"{x0.shape}, {lower.shape}, {upper.shape}")
    if not (np.all(np.isfinite(x0)) and np.all(np.isfinite(lower))
            and np.all(np.isfinite(upper))):
        raise ValueError("x0 and the bounds must be finite")
    if np.any(lower >= upper):
        raise ValueError("every lower bound must be below its upper bound")
    if np.any(x0 < lower) or np.any(x0 > upper):
        raise ValueError("x0 lies outside the bounds")
    if max_evals < 1:
        raise ValueError("max_evals must be at least 1")

    best = {"x": x0.copy(), "f": math.inf, "n": 0}

    def wrapped(x, grad):
        value = float(objective(np.clip(x, lower, upper)))
        best["n"] += 1
        if not math.isfinite(value):  # NaN would poison the methods' models
            value = math.inf
        if value < best["f"]:
            best["f"], best["x"] = value, np.array(x, dtype=np.float64)
        if progress is not None:
            try:
                progress(best["n"], best["f"])
            except Exception as error:  # NLopt swallows exceptions from callbacks: keep it
                best["error"] = error
                raise nlopt.ForcedStop from error
        return value

    opt = nlopt.opt(METHODS[method], x0.size)
    opt.set_lower_bounds(lower)
    opt.set_upper_bounds(upper)
    opt.set_min_objective(wrapped)
    opt.set_maxeval(int(max_evals))
    opt.set_xtol_rel(xtol_rel)
    opt.set_xtol_abs(np.full(x0.size, xtol_abs))
    opt.set_ftol_abs(ftol_abs)
    opt.set_ftol_rel(ftol_rel)
    if max_seconds > 0:
        opt.set_maxtime(max_seconds)
    if stopval is not None:
        opt.set_stopval(stopval)
    step = (upper - lower) / 10.0 if initial_step is None \
        else np.broadcast_to(np.asarray(initial_step, dtype=np.float64), x0.shape)
    opt.set_initial_step(np.asarray(step, dtype=np.float64))

    started = time.perf_counter()
    try:
        opt.optimize(x0)
        stop = STOP_REASONS.get(opt.last_optimize_result(),
                                f"nlopt code {opt.last_optimize_result()}")
    except nlopt.RoundoffLimited:
        stop = "round-off limited"
    except nlopt.ForcedStop:
        if "error" in best:
            raise best["error"] from None
        stop = "forced stop"
    seconds = time.perf_counter() - started
    return OptimizeResult(x=np.clip(best["x"], lower, upper), error=best["f"],
                          evaluations=best["n"], seconds=seconds, method=method, stop=stop)


def minimize_restarted(objective: Callable[[np.ndarray], float], x0, lower, upper, *,
                       restarts: int, restart_gain: float, max_evals: int = 2000,
                       progress: Callable[[int, float], None] | None = None,
                       **options) -> OptimizeResult:
    """``minimize``, then restarted from its best point with fresh models while a restart
    lowers the objective by more than ``restart_gain`` of it (at most ``restarts`` times,
    within ``max_evals`` evaluations in all): a quadratic model goes stale where the objective
    is piecewise smooth, and BOBYQA then stops early on its ftol test. The result's
    evaluations and seconds count every run; ``progress`` gets the evaluations so far and the
    best objective over every run."""
    done, best_so_far = 0, math.inf

    def counted(evaluations, best):
        # Each run counts its own evaluations and best; the caller is told the whole fit's.
        nonlocal best_so_far
        best_so_far = min(best_so_far, best)
        if progress is not None:
            progress(done + evaluations, best_so_far)

    result = minimize(objective, x0, lower, upper, max_evals=max_evals, progress=counted,
                      **options)
    done = result.evaluations
    seconds = result.seconds
    for _ in range(restarts):
        left = max_evals - done
        if left < 4 * len(result.x):
            break
        again = minimize(objective, result.x, lower, upper, max_evals=left, progress=counted,
                         **options)
        done += again.evaluations
        seconds += again.seconds
        gained = result.error - again.error
        if again.error < result.error:
            result = again
        if gained <= restart_gain * abs(result.error):
            break
    result.evaluations, result.seconds = done, seconds
    return result


def with_changes(options: Options, changes: dict[str, Any]) -> Options:
    """A fit's options (a dataclass) with the fields named in ``changes`` replaced: the keyword
    shorthand every fit function takes, ``fit_outline(rig, outline, method="sbplx")`` for
    ``fit_outline(rig, outline, OutlineFit(method="sbplx"))``. TypeError naming a keyword that is
    not one of its fields."""
    if not changes:
        return options
    known = [f.name for f in fields(options)]
    unknown = sorted(set(changes) - set(known))
    if unknown:
        raise TypeError(f"unknown option(s) {', '.join(unknown)} of {type(options).__name__}; "
                        f"it has {', '.join(known)}")
    return replace(options, **changes)
