"""Build step: an articulation target for every phoneme of the inventory (``glasshead.phonemes``).

Writes ``assets/build/phoneme-targets.json`` (``PHONEME_TARGETS_FILE``, format
``PHONEME_TARGETS_FORMAT_VERSION``). For each of the 39 phonemes: every parameter of the tongue
rig (tongue and ``jaw_opening``), of the face rig (lips) and of the velum rig; the per-context
targets (/a i u/) of a measured consonant; the source (the JD3 shape(s) and their fit error, or
the reasoning); the tongue's volume change; the synthetic EPG (8 rows, R1 first) and its emuR
indices; examples and features. docs/targets.md describes every rule below.

How a measured target is made (``target_fits.measured_target``):

1. Coronal: the rig's edge heights from VTL's side elevations, which the mid-sagittal outline
   cannot show: front edges from TS3 (tip), middle from TS2, back from TS1, each clipped to the
   targets' range (``TARGET_CORONAL_RANGES``, ``vtl_mapping.coronal_from_vtl``).
2. Jaw by the sound's class in mm at the incisors (``pipeline.jaw_openings``: vowels by height,
   alveolars VTL's JA within 2 to 5 mm, others VTL's JA), lips from LP, LD and JX, the velum by
   nasality (``fitting.vtl_mapping``).
3. The sagittal parameters (but ``HELD_IN_TARGETS``) fitted to the shape's outline
   (``target_fits.outline_fit``) with the coronal values and the jaw held, refitted with a
   heavier volume weight while the volume is off.
4. Contact (``target_contact``): the consonants of the three real EPG classes and /i/ are fitted
   again with the outline and an EPG error together.

A consonant's own target is its /a/-context fit (the open vowel pulls the tongue least); the /i/
and /u/ fits are kept as ``contexts``. Reasoning-based targets (W, R, HH, Y and AE) are built
from fitted ones as ``glasshead.phonemes`` describes (``REASONED``). The realism rules the
document reports are ``target_realism``'s.

The step is skipped when the SHA-256 of its inputs (the built rig, observations, collision
tables, EPG layout, face and velum rigs, the real EPG recording, and the code: this module and
the others of ``CODE``) is the one the file records.
"""

import hashlib
import inspect
import sys
import time
from pathlib import Path

import numpy as np

from glasshead import phonemes as phoneme_inventory
from glasshead.constants import (
    COLLISION_TABLES_FILE,
    EPG_LAYOUT_FILE,
    FACE_RIG_FILE,
    FACE_RIG_LIP_PARAMETERS,
    LANDMARKS_FILE,
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
from glasshead.fitting import (
    fit2d,
    fit_contact,
    objective2d,
    objective_epg,
    optimizer,
    vtl_mapping,
)
from glasshead.geometry import midsagittal, tongue_surface
from glasshead.pipeline import jaw_openings, target_contact, target_fits, target_realism
from glasshead.pipeline.forked import WORKERS, forked_map
from glasshead.pipeline.outputs import current_output, write_json
from glasshead.pipeline.target_contact import (
    EPG_WEIGHT_OF_GOAL,
    HELD_OF_GOAL,
    JAW_SLACK_OF_GOAL,
    PENETRATION_OF_GOAL,
    RULE_FRAMES_OF_GOAL,
    RULE_GOALS,
    contact_goal,
    measured_target,
    tongue_fit,
)
from glasshead.pipeline.target_fits import (
    ENGASSIM,
    HELD_IN_TARGETS,
    VOLUME_GOAL_PCT,
    Context,
    velum_value,
)
from glasshead.pipeline.target_realism import before_grids, realism

#: Bump when the output changes in a way that must rebuild it.
BUILDER = 3
#: The vowel context a consonant's own target comes from.
MAIN_CONTEXT = "a"
#: The modules whose code shapes the output; their text is part of the cache key.
CODE = (phoneme_inventory, fit2d, objective2d, optimizer, epg_classes, synthetic,
        objective_epg, fit_contact, tongue_surface, epg_contacts, vtl_mapping, midsagittal,
        target_fits, target_contact, target_realism, jaw_openings)
#: Built files read, and the data file.
INPUT_FILES = (TONGUE_RIG_FILE, VTL_OBSERVATIONS_FILE, COLLISION_TABLES_FILE, EPG_LAYOUT_FILE,
               FACE_RIG_FILE, VELUM_RIG_FILE, LANDMARKS_FILE)

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
    for module in (*CODE, sys.modules[__name__]):
        digest.update(inspect.getsource(module).encode())
    digest.update(f"{PHONEME_TARGETS_FORMAT_VERSION}/{BUILDER}".encode())
    return digest.hexdigest()


def _tongue_only(ctx: Context, params: dict) -> dict:
    return {name: value for name, value in params.items() if name in ctx.rig.parameters}


def _finish(ctx: Context, params: dict) -> tuple[dict, np.ndarray]:
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


def fit_tongues(ctx: Context, names: list[str], workers: int = WORKERS) -> dict[str, dict]:
    """``tongue_fit`` of every shape named, by name; the contact fits (the slow ones) first, over
    ``workers`` forked processes that share the context (one process where fork is missing). The
    fits are deterministic, so the result does not depend on the number of workers."""
    order = sorted(names, key=lambda n: contact_goal(ctx, n) is None)
    return dict(zip(order, forked_map(tongue_fit, order, ctx, workers), strict=True))


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
        contact = None
        if symbol in target_contact.CONTACT_OF_REASONED:
            stem = target_contact.CONTACT_OF_REASONED[symbol]
            made = target_contact.reasoned_contact(ctx, params, stem)
            params, contact = {**params, **made["tongue"]}, made["contact"]
        body, grid = _finish(ctx, params)
        grids[symbol] = grid
        previous = targets.get(symbol, {}).get("source", {})
        kind = "fit, adjusted" if previous else "reasoning"
        source = {**previous, "kind": kind, "from": base if base != symbol else None,
                  "adjustment": description,
                  "reasoning": phoneme_inventory.lookup(symbol).reasoning}
        if contact is not None:
            source["contact"] = contact
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
                    "velum": "lowered" if p.velum_lowered else "raised",
                    "epg_basis": epg_basis(t["source"].get("contact")), **t})
    return out, grids


def epg_basis(contact: dict | None) -> str:
    """What a target's palatogram was fitted to: "real EPG" (an engassim class), "published
    descriptions" (a rule goal written from them) or "not fitted" (the 2D fit's contacts)."""
    if not contact:
        return "not fitted"
    return "real EPG" if contact.get("goal_frames") else "published descriptions"


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
        "realism": realism(grids, ctx.classes, before_grids(targets)),
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
