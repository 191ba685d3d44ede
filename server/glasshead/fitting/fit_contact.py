"""Contact fits: the mid-sagittal outline and a wanted EPG pattern together, the volume held.

The 2D fit (``fit2d``) follows JD3's outline, and JD3's palate is not the Reading palate of the
rig's EPG layout: its /t/ touches its own palate 6 mm in front of our first row, so the fitted
targets missed every contact pattern (docs/targets.md). A contact fit minimises, over the free
variables x (mm^2):

    objective2d(x)                      rms^2 of the outline's rays, the volume terms and the
                                        pull toward neutral (``objective2d``, fit2d's weights)
  + epg_weight * E(x)^2                 E: the EPG error (``objective_epg``) of the uncorrected
                                        tongue against the wanted pattern, mm

with the volume bound (4.5 %) made ``VOLUME_BOUND_WEIGHT`` times steeper than the 2D fit's, so
that every fit keeps its volume within 5 % of rest: the tongue is incompressible, and contact
is paid for by lowering another part (the back of the dorsum, the body), not by swelling.
``EPG_WEIGHT`` = 30: a millimetre of EPG error costs as much as 5.5 mm of outline RMS, so the
pattern decides where the tongue meets the palate and the outline shapes the rest. Weaker
weights (4, 10) left /t/'s front row open and its sides free: JD3's outline holds the blade
4 mm under our first row.

A stop must keep its closure when its neighbours in running speech hold the jaw a little more
open than its target does. With ``jaw_slack_deg`` the wanted contacts are asked a second time,
with the jaw that much more open (``ContactObjective.slack_epg``: the wanted electrodes only, so
the target's own pattern is still the first term's): + epg_weight * S(x)^2.

The error aims ``MARGIN_MM`` inside the contact tolerance on both sides (a wanted contact at
most 0.5 mm from its electrode, a free electrode at least 1.5 mm away): the corrected tongue
the synthetic EPG reads can differ from the uncorrected one by a fraction of a millimetre near
the palate, and a margin of 0.3 mm left /t/'s first row open by its two middle electrodes.

Free variables: the 14 sagittal parameters; the jaw, closing only (from the 2D fit's opening,
VTL's JA, a mapping of intent, toward 0); and, left and right alike, coronal groups per section
(``free_groups``): width, edge height and side bulge for side contact, and for the sibilants
also the groove's depth and width (``coronal``). The asymmetries stay at 0. BOBYQA
(``optimizer.minimize``) from the given start, restarted from its best point while a restart
still gains (``RESTARTS``), within ``MAX_EVALS`` evaluations in all.
"""

import time
from collections.abc import Mapping, Sequence
from dataclasses import asdict, dataclass, field

import numpy as np
import numpy.typing as npt

from glasshead.epg.contacts import Probes
from glasshead.fitting import fit2d
from glasshead.fitting.objective2d import MidSagittalSection, Objective2D
from glasshead.fitting.objective_epg import EpgObjective
from glasshead.fitting.optimizer import minimize_restarted, with_changes
from glasshead.geometry.tongue_surface import TongueRig

#: mm^2 per mm^2: weight of the squared EPG error against the squared outline RMS.
EPG_WEIGHT = 30.0
#: mm: the EPG error aims this far inside the contact tolerance on either side, so that the
#: corrected tongue's contacts (which can differ by a fraction of a millimetre) still match.
MARGIN_MM = 0.5
#: mm: a wanted contact the uncorrected tongue overshoots by more than this (past the palate)
#: is penalised too; the correction would flatten it, and the volume would count the overshoot.
PRESS_MM = 2.0
#: The 2D fit's volume bound (4.5 %, 1 mm^2 per percent squared) is made this many times steeper.
VOLUME_BOUND_WEIGHT = 10.0
MAX_EVALS = 2500
#: Restarts of BOBYQA from its best point, while a restart gains more than RESTART_GAIN of the
#: objective.
RESTARTS = 3
RESTART_GAIN = 0.01
#: Coronal groups moved together (left and right alike), by section.
CORONAL_GROUPS = ("width", "groove_depth", "groove_width", "edge_height", "side_bulge")
SECTIONS = ("front", "middle", "back")


@dataclass
class ContactFitReport:
    """One contact fit: the 2D RMS, the EPG error, the predicted and wanted contacts."""

    shape: str
    evaluations: int
    seconds: float
    rms_mm: float
    max_error_mm: float
    epg_error_mm: float
    volume_change_pct: float
    at_limit: list[str]
    stop: str
    params: dict[str, float] = field(default_factory=dict)

    def to_json(self):
        return asdict(self)


def free_groups(rig: TongueRig, sections=SECTIONS, jaw=True,
                coronal=CORONAL_GROUPS, held=()) -> list[tuple[str, list[str]]]:
    """(name, rig parameters) of each free variable: the sagittal ones alone (but those in
    ``held``, which keep their start), the coronal ones per section and group, left and right
    together, and the jaw (closing only, see ``ContactObjective``)."""
    groups = [(name, [name]) for name in fit2d.sagittal_parameters(rig) if name not in held]
    if jaw:
        groups.append((rig.jaw["parameter"], [rig.jaw["parameter"]]))
    for section in sections:
        for group in coronal:
            if group == "edge_height":
                members = [f"{section}_left_edge_height", f"{section}_right_edge_height"]
            else:
                members = [f"{section}_{group}"]
            members = [m for m in members if m in rig.parameters]
            if members:
                groups.append((f"{section}_{group}", members))
    return groups


def group_expansion(groups) -> np.ndarray:
    """(members, groups) 0/1 matrix taking x (one value per group of ``groups``, (name,
    members) pairs) to the members' values, in the order of the groups and their members."""
    sizes = [len(members) for _, members in groups]
    expand = np.zeros((sum(sizes), len(groups)))
    start = 0
    for k, size in enumerate(sizes):
        expand[start:start + size, k] = 1.0
        start += size
    return expand


class ContactObjective:
    """objective2d + epg_weight * E^2 over grouped free variables (see the module docstring)."""

    def __init__(self, rig: TongueRig, outline, epg: EpgObjective, *, base, groups,
                 section: MidSagittalSection | None = None, epg_weight=EPG_WEIGHT,
                 volume_bound_weight=VOLUME_BOUND_WEIGHT * fit2d.VOLUME_BOUND_WEIGHT,
                 slack_epg: EpgObjective | None = None, jaw_slack_deg=0.0, ranges=None):
        self.rig = rig
        self.slack_epg = slack_epg
        self.jaw_slack_deg = float(jaw_slack_deg)
        self.groups = groups
        members = [m for _, ms in groups for m in ms]
        self.plane = Objective2D(rig, outline, members, base=base,
                                 volume_weight=fit2d.VOLUME_WEIGHT,
                                 neutral_weight=fit2d.NEUTRAL_WEIGHT,
                                 volume_bound_pct=fit2d.VOLUME_BOUND_PCT,
                                 volume_bound_weight=volume_bound_weight,
                                 section=section or MidSagittalSection(rig))
        self.expand = group_expansion(groups)
        first = [ms[0] for _, ms in groups]
        index = [rig.parameter_names.index(m) for m in first]
        self.lower, self.upper = rig.minimum[index].copy(), rig.maximum[index].copy()
        # ``ranges``: narrower bounds by coronal group (its name without the section), within
        # the rig's.
        for k, (name, _) in enumerate(groups):
            section, _, group = name.partition("_")
            if ranges and section in SECTIONS and group in ranges:
                low, high = ranges[group]
                self.lower[k] = max(self.lower[k], low)
                self.upper[k] = min(self.upper[k], high)
        base = np.asarray(base, dtype=np.float64)
        jaw = rig.jaw["parameter"]
        if jaw in first:
            # The jaw may close from the 2D fit's opening (VTL's JA, a mapping of intent), not
            # open further: a tongue reaches the palate on a closing jaw at no cost in volume.
            k = first.index(jaw)
            self.upper[k] = max(float(base[rig.jaw_parameter]), self.lower[k] + 1e-3)
        self.x0 = np.clip(base[index], self.lower, self.upper)
        self.epg = epg
        self.epg_weight = float(epg_weight)
        self.evaluations = 0

    def values(self, x) -> np.ndarray:
        return self.plane.values(self.expand @ np.asarray(x, dtype=np.float64))

    def epg_error(self, x) -> float:
        return self.epg(self.rig.vertices(self.values(x)))

    def slackened(self, values) -> np.ndarray:
        """values with the jaw ``jaw_slack_deg`` more open, within its range."""
        out = np.array(values, dtype=np.float64)
        k = self.rig.jaw_parameter
        out[k] = min(out[k] + self.jaw_slack_deg, float(self.rig.maximum[k]))
        return out

    def slack_error(self, x) -> float:
        """The wanted contacts' error with the jaw slackened (0 without ``slack_epg``)."""
        if self.slack_epg is None:
            return 0.0
        return self.slack_epg(self.rig.vertices(self.slackened(self.values(x))))

    def __call__(self, x) -> float:
        self.evaluations += 1
        x = np.asarray(x, dtype=np.float64)
        value = self.plane(self.expand @ x)
        if self.epg_weight:
            value += self.epg_weight * (self.epg_error(x) ** 2 + self.slack_error(x) ** 2)
        return value


@dataclass(frozen=True, eq=False)
class ContactFit:
    """How ``fit_contact`` fits: the method, the free variables (``free_groups``: the coronal
    ``sections`` and ``coronal`` groups, the jaw, the sagittal parameters ``held`` at their
    start), the EPG goal's weights and margins (``objective_epg.EpgObjective``), the steeper
    volume bound, the jaw's slack and narrower coronal ranges. Every field has the fits'
    default."""

    method: str = "bobyqa"
    #: Per electrode, (k,) or an (8, 8) grid, non-negative (default 1).
    weights: npt.ArrayLike | None = None
    sections: Sequence[str] = SECTIONS
    jaw: bool = True
    coronal: Sequence[str] = CORONAL_GROUPS
    held: Sequence[str] = ()
    epg_weight: float = EPG_WEIGHT
    margin: float = MARGIN_MM
    #: The wanted contacts' own margin (``EpgObjective``; default ``margin``).
    contact_margin: float | None = None
    press_mm: float | None = PRESS_MM
    volume_bound_weight: float = VOLUME_BOUND_WEIGHT * fit2d.VOLUME_BOUND_WEIGHT
    #: The wanted contacts are also asked with the jaw this much more open (module docstring).
    jaw_slack_deg: float = 0.0
    #: ``{coronal group: (min, max)}`` narrower than the rig's, for every section.
    ranges: Mapping[str, tuple[float, float]] | None = None
    #: The rig's section, shared by many fits (made from the rig when None).
    section: MidSagittalSection | None = None
    #: The report's shape name.
    name: str = ""

    def groups(self, rig: TongueRig) -> list[tuple[str, list[str]]]:
        """The free variables these options give (``free_groups``)."""
        return free_groups(rig, self.sections, self.jaw, self.coronal, self.held)


def contact_objective(rig: TongueRig, outline, probes: Probes, wanted, base,
                      options: ContactFit | None = None, /, **changes) -> ContactObjective:
    """The ``ContactObjective`` of ``fit_contact`` from ``base`` (P,) values, for an outline
    (n, 2) and a wanted EPG pattern (see there)."""
    options = with_changes(options or ContactFit(), changes)
    epg = EpgObjective(probes, wanted, rig.triangles, weights=options.weights,
                       margin=options.margin, contact_margin=options.contact_margin,
                       press_mm=options.press_mm)
    slack_epg = None
    if options.jaw_slack_deg:
        # Only the wanted contacts, at the plain margin: the closure must be there, and what the
        # looser jaw frees elsewhere is no error.
        slack_epg = EpgObjective(probes, wanted, rig.triangles,
                                 weights=epg.weights * epg.wanted, margin=options.margin)
    return ContactObjective(rig, outline, epg, base=base, groups=options.groups(rig),
                            section=options.section, epg_weight=options.epg_weight,
                            volume_bound_weight=options.volume_bound_weight,
                            slack_epg=slack_epg, jaw_slack_deg=options.jaw_slack_deg,
                            ranges=options.ranges)


def fit_contact(rig: TongueRig, outline, probes: Probes, wanted, base,
                options: ContactFit | None = None, /, *, max_evals: int = MAX_EVALS,
                **changes) -> ContactFitReport:
    """Fit the sagittal and grouped coronal parameters to an outline (n, 2) and a wanted EPG
    pattern (``EpgObjective``'s ``wanted``: per electrode or an (8, 8) grid) from ``base`` (P,)
    values (normally the 2D fit's result, which also holds the jaw and the other parameters),
    within ``max_evals`` evaluations; keyword ``changes`` replace fields of ``options``
    (``optimizer.with_changes``)."""
    options = with_changes(options or ContactFit(), changes)
    objective = contact_objective(rig, outline, probes, wanted, base, options)
    started = time.perf_counter()
    # BOBYQA's quadratic models stall where a ray's crossing jumps (a ray slipping off an edge of
    # the tongue): restart it from its best point, with fresh models, while that still gains.
    result = minimize_restarted(objective, objective.x0, objective.lower, objective.upper,
                                method=options.method, max_evals=max_evals, restarts=RESTARTS,
                                restart_gain=RESTART_GAIN, ftol_abs=fit2d.FTOL_ABS,
                                xtol_abs=fit2d.XTOL_ABS)
    evaluations = result.evaluations
    full = objective.expand @ result.x
    errors = objective.plane.errors(full)
    values = objective.values(result.x)
    plain = EpgObjective(probes, wanted, rig.triangles, weights=options.weights)
    return ContactFitReport(
        shape=options.name, evaluations=evaluations, seconds=time.perf_counter() - started,
        rms_mm=float(np.sqrt(np.mean(errors**2))), max_error_mm=float(np.abs(errors).max()),
        epg_error_mm=plain(rig.vertices(values)),
        volume_change_pct=objective.plane.volume_change(full),
        at_limit=fit2d.at_limit(result.x, objective.lower, objective.upper,
                                [g for g, _ in objective.groups]),
        stop=result.stop,
        params={n: float(v) for n, v in zip(rig.parameter_names, values, strict=True)})
