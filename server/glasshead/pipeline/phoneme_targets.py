"""Build step: an articulation target for every phoneme of the inventory (``glasshead.phonemes``).

Writes ``assets/build/phoneme-targets.json`` (``PHONEME_TARGETS_FILE``, format
``PHONEME_TARGETS_FORMAT_VERSION``). For each of the 39 phonemes: every parameter of the tongue
rig (tongue and ``jaw_opening``), of the face rig (lips) and of the velum rig; the per-context
targets (/a i u/) of a measured consonant; the source (the JD3 shape(s) and their fit error, or
the reasoning); the tongue's volume change; the synthetic EPG (8 rows, R1 first) and its emuR
indices; examples and features. docs/targets.md describes every rule below.

How a measured target is made (``measured_target``):

1. Coronal: the rig's edge heights from VTL's side elevations, which the mid-sagittal outline
   cannot show: front edges from TS3 (tip), middle from TS2, back from TS1, each clipped to the
   targets' range (``TARGET_CORONAL_RANGES``, ``vtl_mapping.coronal_from_vtl``).
2. Jaw from VTL's JA, lips from LP, LD and JX, the velum by nasality
   (``fitting.vtl_mapping``).
3. The sagittal parameters (but ``HELD_IN_TARGETS``) fitted to the shape's outline
   (``fit2d.fit_outline``) with the coronal values and the jaw held; when the tongue's volume
   ends more than ``VOLUME_GOAL_PCT`` from rest the fit is repeated from its result with the
   volume weight ten times heavier, up to three times.
4. Contact (``contact_target``): the shapes of the consonants of the three real EPG classes
   (/t d n/, /s z/, /k g ŋ/, every context) and /i/ are fitted again with the outline and an
   EPG error together (``fitting.fit_contact``): toward the class's real majority pattern
   (``epg.classes``), weighted per electrode by how clear its majority is (for
   /k g ŋ/ the majority of the real frames that close a back row, ``RULE_FRAMES_OF_GOAL``), or
   for /i/ toward the pattern its realism rule describes (``RULE_GOALS``).

A consonant's own target is its /a/-context fit (the open vowel pulls the tongue least); the /i/
and /u/ fits are kept as ``contexts``. Reasoning-based targets (W, R, HH, Y and AE) are built
from fitted ones as ``glasshead.phonemes`` describes (``REASONED``).

The step is skipped when the SHA-256 of its inputs (the built rig, observations, collision
tables, EPG layout, face and velum rigs, the real EPG recording, and the code: this module,
``phonemes``, the fitting, tongue-surface and synthetic EPG modules) is the one the file records.
"""

import hashlib
import inspect
import json
import multiprocessing
import time
from dataclasses import replace
from pathlib import Path

import numpy as np

from glasshead import phonemes as phoneme_inventory
from glasshead.constants import (
    COLLISION_TABLES_FILE,
    EPG_LAYOUT_FILE,
    FACE_RIG_FILE,
    FACE_RIG_LIP_PARAMETERS,
    PHONEME_TARGETS_FILE,
    PHONEME_TARGETS_FORMAT_VERSION,
    TONGUE_RIG_FILE,
    VELUM_PARAMETER,
    VELUM_RIG_FILE,
    VTL_OBSERVATIONS_FILE,
)
from glasshead.epg import classes as epg_classes
from glasshead.epg import contacts as epg_contacts
from glasshead.epg import synthetic
from glasshead.epg.contacts import probes_from_layout
from glasshead.epg.indices import INDEX_SLOTS, epg_indices
from glasshead.epg.sequence import rows_to_strings
from glasshead.fitting import (
    fit2d,
    fit_contact,
    objective2d,
    objective_epg,
    optimizer,
    vtl_mapping,
)
from glasshead.fitting.objective2d import MidSagittalSection
from glasshead.geometry import midsagittal, tongue_surface
from glasshead.geometry.collision_format import decode_collision_tables
from glasshead.geometry.tongue_surface import TongueRig
from glasshead.pipeline.outputs import current_output, write_json

#: Bump when the output changes in a way that must rebuild it.
BUILDER = 3
#: The real EPG recording the realism checks read (under the reference data directory).
ENGASSIM = "epg/emur-engassim.json"
#: Percent: the most a target's tongue volume may differ from rest.
VOLUME_GOAL_PCT = 5.0
#: Percent: the fit is repeated with a heavier volume weight beyond this (a margin under the goal).
VOLUME_REFIT_PCT = 4.5
VOLUME_REFITS = 3
#: The vowel context a consonant's own target comes from.
MAIN_CONTEXT = "a"
#: The modules whose code shapes the output; their text is part of the cache key.
CODE = (phoneme_inventory, fit2d, objective2d, optimizer, epg_classes, synthetic,
        objective_epg, fit_contact, tongue_surface, epg_contacts, vtl_mapping, midsagittal)
#: Built files read, and the data file.
INPUT_FILES = (TONGUE_RIG_FILE, VTL_OBSERVATIONS_FILE, COLLISION_TABLES_FILE, EPG_LAYOUT_FILE,
               FACE_RIG_FILE, VELUM_RIG_FILE)

# --- Fits -----------------------------------------------------------------------------------------


class Context:
    """What every target needs: the rig, its section, the palate's tables and probes, the lip and
    velum tables, the observations by name and, given the data directory, the real EPG classes
    (``epg.classes.class_frames`` of ``ENGASSIM``)."""

    def __init__(self, assets_dir: Path, data_dir: Path | None = None):
        self.rig = TongueRig(json.loads((assets_dir / TONGUE_RIG_FILE).read_text()))
        self.section = MidSagittalSection(self.rig)
        self.rest_volume = self.rig.volume(self.rig.neutral)
        self.tables = decode_collision_tables((assets_dir / COLLISION_TABLES_FILE).read_bytes())
        layout = json.loads((assets_dir / EPG_LAYOUT_FILE).read_text())
        self.probes = probes_from_layout(layout["grids"]["reading62"])
        face = json.loads((assets_dir / FACE_RIG_FILE).read_text())
        self.lip_table = {p["name"]: p for p in face["parameters"]}
        velum = json.loads((assets_dir / VELUM_RIG_FILE).read_text())
        self.velum_table = {p["name"]: p for p in velum["parameters"]}
        observations = json.loads((assets_dir / VTL_OBSERVATIONS_FILE).read_text())
        self.shapes = {s["name"]: s for s in observations["shapes"]}
        self.classes: dict = {}
        if data_dir is not None:
            from glasshead.epg.formats import parse_emur_json

            self.classes = epg_classes.class_frames(
                parse_emur_json((Path(data_dir) / ENGASSIM).read_bytes()))

    def volume_change(self, tongue: dict) -> float:
        return 100.0 * (self.rig.volume(self.rig.values_from(tongue)) / self.rest_volume - 1.0)

    def epg(self, tongue: dict) -> dict:
        """The synthetic EPG of a tongue parameter set: rows (R1 first) and emuR indices."""
        frame = synthetic.synthetic_frame(self.rig, self.rig.values_from(tongue), self.tables,
                                          self.probes)
        values = epg_indices(frame.grid[None])
        return {"rows": rows_to_strings(frame.grid),
                "indices": {name: round(float(values[name][0]), 4) for name in INDEX_SLOTS},
                "grid": frame.grid}


def outline_fit(ctx: Context, shape_name: str) -> tuple[fit2d.FitReport, dict]:
    """The 2D fit of one JD3 shape (steps 1-3 of the module docstring) and its report."""
    rig, shape = ctx.rig, ctx.shapes[shape_name]
    base = rig.neutral.copy()
    base[rig.jaw_parameter] = vtl_mapping.jaw_opening_from_vtl(shape, rig)
    for name, value in vtl_mapping.coronal_from_vtl(
            rig, shape["settings"], TARGET_CORONAL_RANGES["edge_height"]).items():
        base[rig.parameter_names.index(name)] = value
    weight = fit2d.VOLUME_WEIGHT
    free = [n for n in fit2d.sagittal_parameters(rig) if n not in HELD_IN_TARGETS]
    options = fit2d.OutlineFit(free=free, base=base, volume_weight=weight, section=ctx.section,
                               name=shape_name)
    report = fit2d.fit_outline(rig, shape["tongue_outline"], options)
    refits = 0
    while abs(report.volume_change_pct) > VOLUME_REFIT_PCT and refits < VOLUME_REFITS:
        weight *= 10.0
        refits += 1
        options = replace(options, base=rig.values_from(report.params), volume_weight=weight)
        report = fit2d.fit_outline(rig, shape["tongue_outline"], options)
    return report, {"shape": shape_name, "rms_mm": round(report.rms_mm, 3),
                    "max_error_mm": round(report.max_error_mm, 3), "at_limit": report.at_limit,
                    "evaluations": report.evaluations, "volume_weight": weight,
                    "volume_refits": refits}


# --- Contact fits ---------------------------------------------------------------------------------

#: The wanted patterns of vowels with a realism rule and no real EPG frames, written from the
#: rule's text (``RULES``): shape -> (goal name, rule text, per-electrode (wanted, weight) by
#: column of R2-R8 and of R1). /i/: "contact at the sides only": the outer columns (1 and 8)
#: touched in R2-R8, the middle four (3-6) free in every row; columns 2 and 7, and R1's outer
#: electrodes (columns 2 and 7), are what the rule leaves open (weight 0). /a/ ("little or no
#: contact") is left to the 2D fit, which meets it.
RULE_GOALS = {
    "i": ("rule: sides only", "contact at the sides only: outer columns touched in R2-R8, the "
                              "middle four columns free; columns 2 and 7 left open"),
}
#: The coronal groups each goal frees (``fit_contact.CORONAL_GROUPS``): the groove only for the
#: sibilants, whose real frames keep the middle columns open in the front rows.
CORONAL_OF_GOAL = {
    "alveolar_fricative": fit_contact.CORONAL_GROUPS,
    "velar_stop": fit_contact.CORONAL_GROUPS,
}
CORONAL_DEFAULT = ("width", "edge_height", "side_bulge")
#: Sagittal parameters every target's fits hold at neutral. The turn of the tongue's body
#: (``tongue_retraction``) brings the back vowels', velars' and uvulars' outline fits within 1 mm
#: (docs/fitting.md), but the targets' fits then took it for the front vowels and /k/(i) too,
#: in other mixes with the body's straight moves, and in running speech the blend of those mixes
#: left /k/ before /i/ ("Kim") without a closed back row, under the dominance constants trained
#: on targets without it. Until the constants are trained with it, the targets hold it.
#: The front of the dorsum lowered and the root's base drawn in along their rays
#: (``dorsum_front_lowering``, ``root_base_advancement``) bring the last outline fits of /O/, /a/
#: and the velar closure in /a/ within 1 mm; they are held for the same reason.
HELD_IN_TARGETS = ("tongue_retraction", "dorsum_front_lowering", "root_base_advancement")
#: Sagittal parameters a goal's contact fit also holds where the 2D fit put them. The velars'
#: tip: no real /k g/ frame touches the front rows, so the EPG leaves the tip free, and the fits
#: raised it past the alveolars' (the frontmost point of /k/(i) 4.4 mm above /t/(i)'s); in "and
#: Kim" the tip then peaked in /k/ instead of /d/. A velar's tip rests low, where JD3's outline
#: of the velar closure has it.
HELD_OF_GOAL = {"velar_stop": ("tip_advancement", "tip_height", "tip_thickness")}
#: Goals made from only those of the class's real frames that meet its realism rule. Of the 32
#: real /k g/ frames 8 close a back row (R8, in every one of the 8); the other 24 close behind
#: the palate's last row, where no electrode sees the closure, so the majority of all 32 (R8
#: ``11110111``) has no complete row, and targets fitted to it had none either.
RULE_FRAMES_OF_GOAL = {"velar_stop": epg_classes.back_closure}
#: The EPG weight of a goal's contact fit where it is not ``fit_contact.EPG_WEIGHT``: the back
#: row closes only when the dorsum reaches it across its whole width, against the volume bound
#: and JD3's outline; at 30 the velar fits stopped with R8's middle electrodes about 0.5 mm out
#: of reach (/k/(a) and /k/(u): R8 ``11100111``), at 100 they close it.
EPG_WEIGHT_OF_GOAL = {"velar_stop": 100.0}
#: mm, by goal and vowel context: the wanted contacts aimed this far past their electrodes, into
#: the palate (the uncorrected tongue), instead of ``fit_contact.MARGIN_MM`` short of the contact
#: tolerance: a stop must keep its closure when the pose moves a little. Fitted to reach R8 only
#: just, /k/(a) lost R8 with the jaw 0.22 deg more open, as running speech leaves it; aimed 0.5 mm
#: in, /k/(a) and /k/(u) keep a closed row under +-0.3 deg of jaw or +-0.3 mm of any body
#: parameter (tests/test_phoneme_targets.py). Before /i/ a small margin, 0.15 mm: the more it is,
#: the further back the dorsum's highest point, and /k/ is fronted before /i/ against /u/ by
#: 0.65 mm at 0.15 mm, 0.51 mm at 0.2; at 0.1 mm (with the hub following the root) the closure
#: was gone with the jaw 1 deg more open (R8 ``11000011``); at the plain margin it closed no
#: row (R7 ``01111110``).
PENETRATION_OF_GOAL = {"velar_stop": {"a": 0.5, "u": 0.5, "i": 0.15}}
#: Rows (0 = R1) wanted closed across, by goal and vowel context, besides the class's majority:
#: velars are fronted before front vowels, their closure made further forward on the palate
#: (Keating and Lahiri 1993). The engassim closing frames close R8 whatever follows; fitted to
#: them alone, the highest point of /k/(i)'s dorsum came out level with /k/(u)'s or 0.6 mm in
#: front of it, as the last bits of the build fell; wanted closed in R6 and R7 too, it lies
#: about 2 mm in front (docs/targets.md).
FRONTED_ROWS_OF_GOAL = {"velar_stop": {"i": (5, 6)}}
#: Degrees, by goal: the wanted contacts are also asked with the jaw this much more open
#: (``fit_contact``'s ``jaw_slack_deg``). The velar body dominates its neighbours but the jaw
#: does not (docs/coarticulation.md): in "and Kim" the jaw at /k/'s centre stood 0.76 deg more
#: open than /k/(i)'s target, and the target's closure, built on a jaw the fit had closed, was
#: gone (R7 ``11100111``). Asked at 1 deg more open, the closure holds in running speech.
JAW_SLACK_OF_GOAL = {"velar_stop": 1.0}
#: mm: the coronal ranges the targets' fits keep, narrower than the rig's. The rig's were
#: widened for the 3D fits of JD3's surfaces (docs/fitting-3d-fits.md); with them the velar
#: contact fits took other mixes of grooves and widths, and on builds perturbed in the last
#: bits /k/ lost its closure with the jaw 1 deg more open and, in "Kim", in running speech.
TARGET_CORONAL_RANGES = {"width": (-6.0, 6.0), "groove_depth": (-2.0, 6.0),
                         "groove_width": (-2.0, 5.0), "edge_height": (-5.0, 8.0),
                         "side_bulge": (-4.0, 5.0)}


def rule_pattern(shape_name: str) -> tuple[np.ndarray, np.ndarray]:
    """(wanted, weights), (8, 8) each, of a ``RULE_GOALS`` shape (see there)."""
    if shape_name != "i":
        raise KeyError(shape_name)
    wanted = np.zeros((8, 8), dtype=np.uint8)
    weights = epg_classes.ELECTRODES.astype(np.float64)
    wanted[1:, [0, 7]] = 1
    weights[:, [1, 6]] = 0.0
    return wanted, weights


def _context(shape_name: str) -> str | None:
    """The vowel context of a JD3 shape's name ("tb-velar-closure(i)" -> "i"), or None."""
    return shape_name[:-1].split("(")[-1] if shape_name.endswith(")") else None


def contact_goal(ctx: Context, shape_name: str) -> dict | None:
    """What a shape's contact fit aims at, or None when it gets none: ``name`` (the EPG class or
    the rule), ``wanted`` and ``weights`` (8, 8). A class's wanted pattern is its real majority;
    each electrode weighs |2 p - 1|, p the share of the class's frames that touch it, so an
    electrode touched in every frame (or none) counts fully and one touched in half of them not
    at all."""
    stem = shape_name.split("(")[0]
    for name, symbols in epg_classes.PHONEMES_OF.items():
        if name in ctx.classes and any(phoneme_inventory.lookup(s).shape == stem
                                       for s in symbols):
            frames = ctx.classes[name].frames
            if name in RULE_FRAMES_OF_GOAL:
                frames = frames[[RULE_FRAMES_OF_GOAL[name](f) for f in frames]]
            share = frames.mean(axis=0)
            weights = np.abs(2.0 * share - 1.0) * epg_classes.ELECTRODES
            wanted = epg_classes.majority_pattern(frames)
            context = _context(shape_name)
            fronted = list(FRONTED_ROWS_OF_GOAL.get(name, {}).get(context, ()))
            if fronted:
                wanted, weights = wanted.copy(), weights.copy()
                wanted[fronted] = epg_classes.ELECTRODES[fronted]
                weights[fronted] = epg_classes.ELECTRODES[fronted]
            return {"name": name, "wanted": wanted, "fronted_rows": fronted,
                    "weights": weights, "frames": int(len(frames)),
                    "epg_weight": EPG_WEIGHT_OF_GOAL.get(name, fit_contact.EPG_WEIGHT),
                    "penetration_mm": PENETRATION_OF_GOAL.get(name, {}).get(context)}
    if shape_name in RULE_GOALS:
        wanted, weights = rule_pattern(shape_name)
        return {"name": RULE_GOALS[shape_name][0], "wanted": wanted, "weights": weights,
                "rule": RULE_GOALS[shape_name][1], "epg_weight": fit_contact.EPG_WEIGHT}
    return None


def _agreement(grid, goal) -> float:
    """Share of the electrodes with weight that agree with the goal's wanted pattern (for a class:
    of all 62, as ``epg_classes.agreement``)."""
    if "frames" in goal:
        return epg_classes.agreement(grid, goal["wanted"])
    counted = goal["weights"] > 0
    return float(((np.asarray(grid) == goal["wanted"]) & counted).sum() / counted.sum())


def _contact_start(ctx: Context, objective: fit_contact.ContactObjective, fitted) -> np.ndarray:
    """The better start (lower objective) of the 2D fit's result and the rest tongue (with the 2D
    fit's jaw and VTL's edge heights): a 2D fit of an open-vowel context can leave the tongue so
    far below the palate that BOBYQA stalls before it gets there."""
    rig = ctx.rig
    rest = rig.neutral.copy()
    rest[rig.jaw_parameter] = fitted[rig.jaw_parameter]
    for k, name in enumerate(rig.parameter_names):
        if name.endswith("_edge_height"):
            rest[k] = fitted[k]
    index = [rig.parameter_names.index(members[0]) for _, members in objective.groups]
    candidates = [objective.x0, np.clip(rest[index], objective.lower, objective.upper)]
    return min(candidates, key=objective)


def tongue_fit(ctx: Context, shape_name: str) -> dict:
    """The tongue of one JD3 shape: the 2D fit and, for the shapes with a contact goal, the
    contact fit from it. Returns ``tongue`` (rig values by name) and ``fit`` (the report)."""
    rig, shape = ctx.rig, ctx.shapes[shape_name]
    report, fit = outline_fit(ctx, shape_name)
    goal = contact_goal(ctx, shape_name)
    if goal is None:
        return {"tongue": {n: round(v, 4) for n, v in report.params.items()}, "fit": fit}
    fitted = rig.values_from(report.params)
    plain = objective_epg.EpgObjective(ctx.probes, goal["wanted"], rig.triangles,
                                       weights=goal["weights"])
    before_grid = ctx.epg(report.params)["grid"]
    coronal = CORONAL_OF_GOAL.get(goal["name"], CORONAL_DEFAULT)
    held = HELD_IN_TARGETS + HELD_OF_GOAL.get(goal["name"], ())
    penetration = goal.get("penetration_mm")
    jaw_slack = JAW_SLACK_OF_GOAL.get(goal["name"], 0.0)
    contact_margin = None if penetration is None else ctx.probes.tolerance + penetration
    options = fit_contact.ContactFit(
        weights=goal["weights"], coronal=coronal, held=held, epg_weight=goal["epg_weight"],
        contact_margin=contact_margin, jaw_slack_deg=jaw_slack, ranges=TARGET_CORONAL_RANGES,
        section=ctx.section, name=shape_name)
    objective = fit_contact.contact_objective(rig, shape["tongue_outline"], ctx.probes,
                                              goal["wanted"], fitted, options)
    start = _contact_start(ctx, objective, fitted)
    contact = fit_contact.fit_contact(rig, shape["tongue_outline"], ctx.probes, goal["wanted"],
                                      objective.values(start), options)
    tongue = {n: round(v, 4) for n, v in contact.params.items()}
    after_grid = ctx.epg(tongue)["grid"]
    fit = {**fit, "rms_mm": round(contact.rms_mm, 3),
           "max_error_mm": round(contact.max_error_mm, 3), "at_limit": contact.at_limit,
           "evaluations": fit["evaluations"] + contact.evaluations,
           "contact": {"goal": goal["name"], "rule": goal.get("rule"),
                       "epg_error_mm": round(contact.epg_error_mm, 3),
                       "agreement": round(_agreement(after_grid, goal), 4),
                       "evaluations": contact.evaluations, "seconds": round(contact.seconds, 2),
                       "stop": contact.stop, "coronal": list(coronal),
                       "epg_weight": goal["epg_weight"], "goal_frames": goal.get("frames"),
                       "fronted_rows": [r + 1 for r in goal.get("fronted_rows", [])],
                       "penetration_mm": penetration,
                       "before": {"rms_mm": fit["rms_mm"],
                                  "epg_error_mm": round(plain(rig.vertices(fitted)), 3),
                                  "agreement": round(_agreement(before_grid, goal), 4),
                                  "rows": rows_to_strings(before_grid),
                                  "volume_change_pct": round(report.volume_change_pct, 3)}}}
    return {"tongue": tongue, "fit": fit}


def measured_target(ctx: Context, shape_name: str, nasal: bool, made: dict | None = None) -> dict:
    """The fitted target of one JD3 shape: params (all rigs) and the fit report; ``made`` is the
    shape's ``tongue_fit`` when already done."""
    made = made or tongue_fit(ctx, shape_name)
    tongue = made["tongue"]
    jaw = tongue[ctx.rig.jaw["parameter"]]
    params = {**tongue, **vtl_mapping.lips_from_vtl(ctx.shapes[shape_name]["settings"], jaw,
                                                 ctx.lip_table),
              VELUM_PARAMETER: velum_value(ctx, nasal)}
    return {"params": params, "fit": made["fit"]}


def velum_value(ctx: Context, nasal: bool) -> float:
    return vtl_mapping.velum_of(nasal, ctx.velum_table[VELUM_PARAMETER])


# --- Reasoning-based targets ----------------------------------------------------------------------


def _shift(ctx: Context, params: dict, changes: dict) -> dict:
    """params with each named value moved by ``changes[name]`` (or set, for "=value" strings),
    clipped to its rig's range."""
    tables = {**ctx.rig.parameters, **ctx.lip_table, **ctx.velum_table}
    out = dict(params)
    for name, change in changes.items():
        value = float(change[1:]) if isinstance(change, str) else out[name] + change
        out[name] = round(vtl_mapping.clip(tables[name], value), 4)
    return out


#: How each reasoning-based target is made from a fitted one (glasshead.phonemes's reasoning):
#: (phoneme, base target, changes, description).
REASONED = (
    ("W", "UW", {"lip_rounding": 3.0, "lip_protrusion": 2.0, "lip_opening": "=0.3"},
     "the /u/ target with the lips rounded 3 mm and protruded 2 mm further (clipped to the rig's "
     "ranges) and their opening narrowed to 0.3 of the jaw's gap"),
    ("R", "SH", {"tip_height": -4.0, "blade_height": -2.0, "root_advancement": -3.0,
                 "front_left_edge_height": "=0", "front_right_edge_height": "=0",
                 "lip_rounding": 2.0, "lip_protrusion": 1.0},
     "the postalveolar fricative target with the tip lowered 4 mm, the blade lowered 2 mm (a gap "
     "kept from the palate), the root retracted 3 mm, no sibilant groove (front edges neutral) "
     "and the lips rounded 2 mm and protruded 1 mm further"),
    ("Y", "Y", {"dorsum_height": -2.0, "blade_height": -2.0},
     "the palatal fricative fit with the dorsum and blade lowered 2 mm (an approximant is wider)"),
    ("AE", "AE", {"jaw_opening": 2.0},
     "the /ɛ/ fit with the jaw opened 2 degrees further (clipped to the rig's range)"),
)


def neutral_target(ctx: Context) -> dict:
    """The rig's rest pose for every parameter, the velum raised."""
    params = {name: float(spec["neutral"]) for name, spec in ctx.rig.parameters.items()}
    params.update({name: float(spec["neutral"]) for name, spec in ctx.lip_table.items()})
    params[VELUM_PARAMETER] = velum_value(ctx, False)
    return params


# --- The build ------------------------------------------------------------------------------------


def input_key(assets_dir: Path, data_dir: Path) -> str:
    digest = hashlib.sha256()
    for name in INPUT_FILES:
        digest.update(name.encode() + b"\0" + (assets_dir / name).read_bytes() + b"\0")
    digest.update((data_dir / ENGASSIM).read_bytes())
    for module in (*CODE, inspect.getmodule(input_key)):
        digest.update(inspect.getsource(module).encode())
    digest.update(f"{PHONEME_TARGETS_FORMAT_VERSION}/{BUILDER}".encode())
    return digest.hexdigest()


def _tongue_only(ctx: Context, params: dict) -> dict:
    return {name: value for name, value in params.items() if name in ctx.rig.parameters}


def _finish(ctx: Context, params: dict) -> dict:
    """Volume and synthetic EPG of a parameter set."""
    tongue = _tongue_only(ctx, params)
    epg = ctx.epg(tongue)
    return {"params": params, "volume_change_pct": round(ctx.volume_change(tongue), 3),
            "epg": {"rows": epg["rows"], "indices": epg["indices"]}}, epg["grid"]


def _features(p) -> dict:
    return {"voiced": p.voiced, "nasal": p.nasal, "place": p.place, "manner": p.manner,
            "rounded": p.rounded}


def shape_names() -> list[str]:
    """Every JD3 shape a target is fitted to, once, in inventory order."""
    names: list[str] = []
    for p in phoneme_inventory.INVENTORY:
        if p.shape is None:
            continue
        for name in ([f"{p.shape}({c})" for c in p.contexts] if p.contexts else [p.shape]):
            if name not in names:
                names.append(name)
    return names


#: Worker processes for the fits (each fit is single-threaded numpy).
WORKERS = 2
_POOL_CONTEXT: Context | None = None


def _tongue_job(shape_name: str) -> dict:
    assert _POOL_CONTEXT is not None
    return tongue_fit(_POOL_CONTEXT, shape_name)


def fit_tongues(ctx: Context, names: list[str], workers: int = WORKERS) -> dict[str, dict]:
    """``tongue_fit`` of every shape named, by name; the contact fits (the slow ones) first, over
    ``workers`` forked processes that share the context (one process where fork is missing). The
    fits are deterministic, so the result does not depend on the number of workers."""
    global _POOL_CONTEXT
    order = sorted(names, key=lambda n: contact_goal(ctx, n) is None)
    if workers > 1 and "fork" in multiprocessing.get_all_start_methods():
        _POOL_CONTEXT = ctx
        try:
            with multiprocessing.get_context("fork").Pool(workers) as pool:
                made = pool.map(_tongue_job, order, chunksize=1)
        finally:
            _POOL_CONTEXT = None
    else:
        made = [tongue_fit(ctx, name) for name in order]
    return dict(zip(order, made, strict=True))


def build_targets(ctx: Context) -> tuple[list[dict], dict]:
    """Every phoneme's target in inventory order, and the synthetic grids by ARPAbet symbol."""
    targets: dict[str, dict] = {}
    grids: dict[str, np.ndarray] = {}
    tongues = fit_tongues(ctx, shape_names())

    def fitted(shape_name, nasal):
        return measured_target(ctx, shape_name, nasal, tongues[shape_name])

    for p in phoneme_inventory.INVENTORY:
        if p.shape is None:
            continue
        if p.contexts:
            contexts = {}
            for c in p.contexts:
                made = fitted(f"{p.shape}({c})", p.nasal)
                body, grid = _finish(ctx, made["params"])
                contexts[c] = {**body, "fit": made["fit"]}
                if c == MAIN_CONTEXT:
                    grids[p.arpabet] = grid
            main = contexts[MAIN_CONTEXT]
            source = {"kind": "fit", "shapes": [f"{p.shape}({c})" for c in p.contexts],
                      "main_shape": main["fit"]["shape"], "rms_mm": main["fit"]["rms_mm"],
                      "max_error_mm": main["fit"]["max_error_mm"],
                      "at_limit": main["fit"]["at_limit"],
                      "context_rms_mm": {c: contexts[c]["fit"]["rms_mm"] for c in contexts},
                      "reasoning": p.reasoning}
            if "contact" in main["fit"]:
                source["contact"] = main["fit"]["contact"]
            targets[p.arpabet] = {"params": main["params"], "contexts": contexts,
                                  "volume_change_pct": main["volume_change_pct"],
                                  "epg": main["epg"], "source": source}
        else:
            made = fitted(p.shape, p.nasal)
            body, grid = _finish(ctx, made["params"])
            grids[p.arpabet] = grid
            targets[p.arpabet] = {**body, "contexts": {}, "source": {
                "kind": "fit", "shapes": [p.shape], "main_shape": p.shape,
                "rms_mm": made["fit"]["rms_mm"], "max_error_mm": made["fit"]["max_error_mm"],
                "at_limit": made["fit"]["at_limit"], "reasoning": p.reasoning}}
            if "contact" in made["fit"]:
                targets[p.arpabet]["source"]["contact"] = made["fit"]["contact"]

    for symbol, base, changes, description in REASONED:
        params = _shift(ctx, targets[base]["params"], changes)
        body, grid = _finish(ctx, params)
        grids[symbol] = grid
        previous = targets.get(symbol, {}).get("source", {})
        kind = "fit, adjusted" if previous else "reasoning"
        source = {**previous, "kind": kind, "from": base if base != symbol else None,
                  "adjustment": description,
                  "reasoning": phoneme_inventory.lookup(symbol).reasoning}
        targets[symbol] = {**body, "contexts": targets.get(symbol, {}).get("contexts", {}),
                           "source": source}

    body, grid = _finish(ctx, neutral_target(ctx))
    grids["HH"] = grid
    targets["HH"] = {**body, "contexts": {}, "source": {
        "kind": "reasoning", "from": None, "adjustment": "the rig's rest pose",
        "reasoning": phoneme_inventory.lookup("HH").reasoning}}

    out = []
    for p in phoneme_inventory.INVENTORY:
        t = targets[p.arpabet]
        out.append({"arpabet": p.arpabet, "ipa": p.ipa, "kind": p.kind,
                    "examples": list(p.examples), "features": _features(p),
                    "velum": "lowered" if p.velum_lowered else "raised", **t})
    return out, grids


#: The realism rules: (phonemes, rule name, test of a grid).
def _sides_only(grid) -> bool:
    grid = np.asarray(grid).astype(bool)
    middle = grid[:, 2:6].sum()
    return epg_classes.side_contact(grid) and middle <= 2


def _little_contact(grid) -> bool:
    return int(np.asarray(grid).sum()) <= 6


RULES = (
    (("T", "D", "N"), "complete closure across a front row with contact along both sides",
     lambda g: epg_classes.front_closure(g) and epg_classes.side_contact(g)),
    (("S", "Z"), "contact along the sides with a central groove open in the front rows",
     epg_classes.central_groove),
    (("K", "G"), "complete closure across a back row", epg_classes.back_closure),
    (("IY",), "contact at the sides only (outer columns in most rows, at most 2 of the middle "
              "four columns' electrodes)", _sides_only),
    (("AA",), "little or no contact (at most 6 electrodes)", _little_contact),
)


def _grid(rows) -> np.ndarray:
    return np.array([[int(c) for c in r] for r in rows], dtype=np.uint8)


def realism(grids: dict, classes: dict, before: dict | None = None) -> dict:
    """The five rules per phoneme, and each EPG class's agreement with its phonemes' patterns;
    ``before``: the 2D fits' grids of the contact-fitted targets (by symbol), reported beside.
    Each class also says how many of its own real frames pass its rule."""
    before = before or {}
    checks = []
    for symbols, rule, test in RULES:
        for symbol in symbols:
            check = {"phoneme": symbol, "rule": rule, "pass": bool(test(grids[symbol])),
                     "rows": rows_to_strings(grids[symbol])}
            if symbol in before:
                check["pass_before_contact_fit"] = bool(test(before[symbol]))
            checks.append(check)
    shares = {}
    for name, frames in classes.items():
        majority = frames.majority
        test = next(t for symbols, _, t in RULES
                    if set(symbols) & set(epg_classes.PHONEMES_OF[name]))
        shares[name] = {
            "frames": int(len(frames.frames)),
            "majority": rows_to_strings(majority),
            "real_frames_passing_rule": round(float(np.mean([test(f) for f in frames.frames])),
                                              4),
            "majority_passes_rule": bool(test(majority)),
            "agreement": {s: round(epg_classes.agreement(grids[s], majority), 4)
                          for s in epg_classes.PHONEMES_OF[name]},
            "agreement_before_contact_fit": {
                s: round(epg_classes.agreement(before[s], majority), 4)
                for s in epg_classes.PHONEMES_OF[name] if s in before}}
    return {"rules": checks, "passed": sum(c["pass"] for c in checks), "of": len(checks),
            "passed_before_contact_fit": sum(c.get("pass_before_contact_fit", c["pass"])
                                             for c in checks),
            "agreement": shares}


def _before_grids(targets: list[dict]) -> dict:
    """The 2D fits' grids of the contact-fitted targets' own (main) shapes, by symbol."""
    out = {}
    for t in targets:
        contact = t["source"].get("contact")
        if contact:
            out[t["arpabet"]] = _grid(contact["before"]["rows"])
    return out


def build_phoneme_targets(assets_dir, data_dir, out_path=None, force=False):
    """Write the targets; returns (document, skipped)."""
    assets_dir, data_dir = Path(assets_dir), Path(data_dir)
    out_path = Path(out_path) if out_path else assets_dir / PHONEME_TARGETS_FILE
    digest = input_key(assets_dir, data_dir)
    existing = None if force else current_output(out_path, digest, BUILDER,
                                                 PHONEME_TARGETS_FORMAT_VERSION)
    if existing is not None:
        return existing, True
    started = time.perf_counter()
    ctx = Context(assets_dir, data_dir)
    targets, grids = build_targets(ctx)
    document = {
        "format_version": PHONEME_TARGETS_FORMAT_VERSION,
        "builder": BUILDER,
        "source": {"sha256": digest, "inputs": [*INPUT_FILES, ENGASSIM]},
        "parameters": {"tongue": list(ctx.rig.parameter_names),
                       "lips": list(FACE_RIG_LIP_PARAMETERS), "velum": [VELUM_PARAMETER]},
        "main_context": MAIN_CONTEXT,
        "mapping": vtl_mapping.MAPPING_TEXT,
        "volume_goal_pct": VOLUME_GOAL_PCT,
        "count": len(targets),
        "targets": targets,
        "contact_fit": {"epg_weight": fit_contact.EPG_WEIGHT, "margin_mm": fit_contact.MARGIN_MM,
                        "press_mm": fit_contact.PRESS_MM, "rule_goals": dict(RULE_GOALS),
                        "epg_weight_of_goal": dict(EPG_WEIGHT_OF_GOAL),
                        "penetration_mm_of_goal": {k: dict(v) for k, v
                                                   in PENETRATION_OF_GOAL.items()},
                        "held": list(HELD_IN_TARGETS),
                        "held_of_goal": {k: list(v) for k, v in HELD_OF_GOAL.items()},
                        "jaw_slack_deg_of_goal": dict(JAW_SLACK_OF_GOAL),
                        "rule_frames_of_goal": {name: test.__name__ for name, test
                                                in RULE_FRAMES_OF_GOAL.items()},
                        "weights": "|2 p - 1| per electrode, p the share of the class's real "
                                   "frames touching it"},
        "realism": realism(grids, ctx.classes, _before_grids(targets)),
        "build_seconds": round(time.perf_counter() - started, 3),
    }
    out_path.parent.mkdir(parents=True, exist_ok=True)
    write_json(out_path, document)
    return document, False


def _report_line(target: dict) -> dict:
    """A target's line in the build report: its source, 2D RMS, volume change and, when contact
    fitted, its EPG error and agreement (before and after the contact fit)."""
    line = {"source": target["source"]["kind"], "rms_mm": target["source"].get("rms_mm"),
            "volume_change_pct": target["volume_change_pct"]}
    contact = target["source"].get("contact")
    if contact:
        line.update({"goal": contact["goal"], "epg_error_mm": contact["epg_error_mm"],
                     "agreement": contact["agreement"],
                     "before": {k: contact["before"][k] for k in
                                ("rms_mm", "epg_error_mm", "agreement", "volume_change_pct")}})
    return line


def build_step(ctx) -> dict:
    """``glasshead build`` step: the report lists each target's fit RMS and volume change, the
    realism rules (before and after the contact fits) and the agreement shares."""
    document, skipped = build_phoneme_targets(ctx.assets_dir, ctx.data_dir)
    return {"step": "phoneme-targets", "skipped": skipped, "count": document["count"],
            "build_seconds": document["build_seconds"],
            "targets": {t["arpabet"]: _report_line(t) for t in document["targets"]},
            "realism": {"passed": document["realism"]["passed"],
                        "of": document["realism"]["of"],
                        "passed_before_contact_fit":
                            document["realism"]["passed_before_contact_fit"],
                        "rules": [{k: r[k] for k in ("phoneme", "rule", "pass")}
                                  for r in document["realism"]["rules"]]},
            "agreement": {name: c["agreement"]
                          for name, c in document["realism"]["agreement"].items()}}
