"""Contact fits of the phoneme targets: step 4 of ``pipeline.phoneme_targets`` (docs/targets.md).

The shapes of the consonants of the three real EPG classes (/t d n/, /s z/, /k g ŋ/, every
context), /ʃ ʒ/, /l/, /tʃ dʒ/ and /i/ are fitted again with the outline and an EPG error together
(``fitting.fit_contact``): toward the class's real majority pattern (``epg.classes``), weighted
per electrode by how clear its majority is (for /k g ŋ/ the majority of the real frames that
close a back row, ``RULE_FRAMES_OF_GOAL``), or for the others toward the pattern published
descriptions and the realism rule give (``RULE_GOALS``). ``tongue_fit`` is a shape's whole
tongue: the 2D fit (``target_fits.outline_fit``) and, for a shape with a goal
(``contact_goal``), the contact fit from it; ``measured_target`` adds the lips and the velum.
"""

import numpy as np

from glasshead import phonemes as phoneme_inventory
from glasshead.constants import VELUM_PARAMETER
from glasshead.epg import classes as epg_classes
from glasshead.epg.sequence import rows_to_strings
from glasshead.fitting import fit_contact, objective_epg, vtl_mapping
from glasshead.fitting.authored import own_outline
from glasshead.pipeline.target_fits import (
    HELD_IN_TARGETS,
    TARGET_CORONAL_RANGES,
    Context,
    outline_fit,
    velum_value,
)

#: The wanted patterns of vowels with a realism rule and no real EPG frames, written from the
#: rule's text (``RULES``): shape -> (goal name, rule text, per-electrode (wanted, weight) by
#: column of R2-R8 and of R1). /i/: "contact at the sides only": the outer columns (1 and 8)
#: touched in R2-R8, the middle four (3-6) free in every row; columns 2 and 7, and R1's outer
#: electrodes (columns 2 and 7), are what the rule leaves open (weight 0). /a/ ("little or no
#: contact") is left to the 2D fit, which meets it.
#: /ʃ ʒ/ (JD3's postalveolar fricative), which engassim has no frames of: published EPG of
#: English /ʃ/ shows a groove wider than /s/'s and further back, with lateral contact along the
#: sides and little contact in the front row (Hardcastle, Gibbon and Jones 1991; Gibbon and
#: Nicolaidis 1999). Wanted: the outer columns touched in R2-R5, the middle four columns free in
#: R1-R4; columns 2 and 7 of R2-R5, R1's outer electrodes and R6-R8 left open.
RULE_GOALS = {
    "i": ("rule: sides only", "contact at the sides only: outer columns touched in R2-R8, the "
                              "middle four columns free; columns 2 and 7 left open"),
    "tt-postalveolar-fricative": (
        "rule: postalveolar groove",
        "published descriptions of English /ʃ/: a groove wider than /s/'s and further back, "
        "outer columns touched in R2-R5, the middle four columns free in R1-R4"),
    "tt-alveolar-lateral": (
        "rule: alveolar lateral",
        "published descriptions of English /l/: the tip on the alveolar ridge (the middle four "
        "columns of R1-R2 touched) with the sides free behind it for the air (no contact in "
        "columns 1, 2, 7 and 8 of R3-R8)"),
    "tt-postalveolar-closure": (
        "rule: postalveolar closure",
        "published descriptions of English /tʃ dʒ/: a complete closure across R2 and R3, "
        "further back than /t/'s, with contact along both sides (outer columns of R4-R8)"),
    "rhotic": (
        "rule: rhotic lateral",
        "published descriptions of English /r/: contact along the lateral margins of the back "
        "of the palate (the outer columns of R4-R8), none in the front rows (R1-R2) or in the "
        "middle four columns, where the air passes"),
}
#: Reasoned targets (``phoneme_targets.REASONED``) fitted from their reasoned pose toward a rule
#: goal, their own outline held (``reasoned_contact``): /ɹ/, made from /ʃ/'s fit with the tip
#: and blade lowered, touched nothing; a real /r/ touches the sides of the back of the palate.
CONTACT_OF_REASONED = {"R": "rhotic"}
#: The coronal groups each goal frees (``fit_contact.CORONAL_GROUPS``): the groove only for the
#: sibilants, whose real frames keep the middle columns open in the front rows.
CORONAL_OF_GOAL = {
    "alveolar_fricative": fit_contact.CORONAL_GROUPS,
    "rule: postalveolar groove": fit_contact.CORONAL_GROUPS,
    "velar_stop": fit_contact.CORONAL_GROUPS,
}
CORONAL_DEFAULT = ("width", "edge_height", "side_bulge")
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
#: of reach (/k/(a) and /k/(u): R8 ``11100111``), at 100 they close it. The alveolar stops too:
#: at 30 /t d n/ agreed 0.82 with their class (the sides free in R3-R5 and R7 where the real
#: frames touch them), at 100 0.85.
EPG_WEIGHT_OF_GOAL = {"velar_stop": 100.0, "rule: postalveolar closure": 100.0,
                      "alveolar_stop": 100.0}
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
FRONTED_ROWS_OF_GOAL: dict[str, dict[str, tuple[int, ...]]] = {"velar_stop": {"i": (5, 6)}}
#: Degrees, by goal: the wanted contacts are also asked with the jaw this much more open
#: (``fit_contact``'s ``jaw_slack_deg``). The velar body dominates its neighbours but the jaw
#: does not (docs/coarticulation.md): in "and Kim" the jaw at /k/'s centre stood 0.76 deg more
#: open than /k/(i)'s target, and the target's closure, built on a jaw the fit had closed, was
#: gone (R7 ``11100111``). Asked at 1 deg more open, the closure holds in running speech.
JAW_SLACK_OF_GOAL = {"velar_stop": 1.0}
def rule_pattern(shape_name: str) -> tuple[np.ndarray, np.ndarray]:
    """(wanted, weights), (8, 8) each, of a ``RULE_GOALS`` shape or shape stem (see there)."""
    stem = shape_name.split("(")[0]
    wanted = np.zeros((8, 8), dtype=np.uint8)
    weights = epg_classes.ELECTRODES.astype(np.float64)
    if stem == "i":
        wanted[1:, [0, 7]] = 1
        weights[:, [1, 6]] = 0.0
    elif stem == "tt-postalveolar-fricative":
        wanted[1:5, [0, 7]] = 1
        weights[1:5, [1, 6]] = 0.0
        weights[0, [1, 6]] = 0.0
        weights[5:] = 0.0
    elif stem == "tt-alveolar-lateral":
        weights[:] = 0.0
        wanted[:2, 2:6] = 1
        weights[:2, 2:6] = 1.0
        weights[2:, [0, 1, 6, 7]] = 1.0
    elif stem == "tt-postalveolar-closure":
        weights[:] = 0.0
        wanted[1:3] = 1
        weights[1:3] = 1.0
        wanted[3:, [0, 7]] = 1
        weights[3:, [0, 7]] = 1.0
    elif stem == "rhotic":
        weights[:] = 0.0
        weights[:2] = epg_classes.ELECTRODES[:2]
        weights[2:, 2:6] = 1.0
        wanted[3:, [0, 7]] = 1
        weights[3:, [0, 7]] = 1.0
    else:
        raise KeyError(shape_name)
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
            fronted = list(FRONTED_ROWS_OF_GOAL.get(name, {}).get(context or "", ()))
            if fronted:
                wanted, weights = wanted.copy(), weights.copy()
                wanted[fronted] = epg_classes.ELECTRODES[fronted]
                weights[fronted] = epg_classes.ELECTRODES[fronted]
            return {"name": name, "wanted": wanted, "fronted_rows": fronted,
                    "weights": weights, "frames": int(len(frames)),
                    "epg_weight": EPG_WEIGHT_OF_GOAL.get(name, fit_contact.EPG_WEIGHT),
                    "penetration_mm": PENETRATION_OF_GOAL.get(name, {}).get(context or "")}
    if stem in RULE_GOALS:
        wanted, weights = rule_pattern(stem)
        name = RULE_GOALS[stem][0]
        return {"name": name, "wanted": wanted, "weights": weights,
                "rule": RULE_GOALS[stem][1],
                "epg_weight": EPG_WEIGHT_OF_GOAL.get(name, fit_contact.EPG_WEIGHT)}
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


def reasoned_contact(ctx: Context, params: dict, stem: str) -> dict:
    """A reasoned target's contact fit toward the rule goal ``stem`` (``RULE_GOALS``), from its
    reasoned pose, with that pose's own mid-sagittal outline as the outline term: the shape the
    reasoning gave is kept, and the sides and the body meet the palate where the rule wants.
    Returns ``tongue`` (rig values by name) and ``contact`` (the report, as ``tongue_fit``'s)."""
    rig = ctx.rig
    reasoned = {n: params[n] for n in rig.parameter_names}
    values = rig.values_from(reasoned)
    outline = own_outline(ctx.section, values)
    wanted, weights = rule_pattern(stem)
    name, rule = RULE_GOALS[stem]
    goal = {"name": name, "wanted": wanted, "weights": weights}
    epg_weight = EPG_WEIGHT_OF_GOAL.get(name, fit_contact.EPG_WEIGHT)
    options = fit_contact.ContactFit(
        weights=weights, coronal=CORONAL_DEFAULT, held=HELD_IN_TARGETS, epg_weight=epg_weight,
        ranges=TARGET_CORONAL_RANGES, section=ctx.section, name=stem)
    before_grid = ctx.epg(reasoned)["grid"]
    contact = fit_contact.fit_contact(rig, outline, ctx.probes, wanted, values, options)
    tongue = {n: round(v, 4) for n, v in contact.params.items()}
    after_grid = ctx.epg(tongue)["grid"]
    return {"tongue": tongue, "contact": {
        "goal": name, "rule": rule, "epg_error_mm": round(contact.epg_error_mm, 3),
        "agreement": round(_agreement(after_grid, goal), 4),
        "evaluations": contact.evaluations, "seconds": round(contact.seconds, 2),
        "stop": contact.stop, "coronal": list(CORONAL_DEFAULT), "epg_weight": epg_weight,
        "goal_frames": None, "outline": "its own reasoned pose's",
        "rms_mm": round(contact.rms_mm, 3),
        "before": {"rms_mm": 0.0,
                   "epg_error_mm": round(objective_epg.EpgObjective(
                       ctx.probes, wanted, rig.triangles, weights=weights)(
                       rig.vertices(values)), 3),
                   "agreement": round(_agreement(before_grid, goal), 4),
                   "rows": rows_to_strings(before_grid),
                   "volume_change_pct": round(ctx.volume_change(reasoned), 3)}}}


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
