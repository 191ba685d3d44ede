"""The realism rules of the phoneme targets' synthetic EPG (docs/targets.md, "Realism"): one
rule per phoneme the real EPG or published descriptions speak for, and each EPG class's
agreement with its phonemes' patterns, before and after the contact fits."""

import numpy as np

from glasshead.epg import classes as epg_classes
from glasshead.epg.sequence import rows_to_strings


#: The realism rules: (phonemes, rule name, test of a grid).
def _sides_only(grid) -> bool:
    grid = np.asarray(grid).astype(bool)
    middle = grid[:, 2:6].sum()
    return epg_classes.side_contact(grid) and middle <= 2


def _postalveolar_groove(grid) -> bool:
    """Sides touched in R2-R5 (the outer column in at least 3 of the 4 rows, each side) and the
    middle four columns free in R1-R4 (at most one electrode)."""
    grid = np.asarray(grid).astype(bool)
    sides = grid[1:5, 0].sum() >= 3 and grid[1:5, 7].sum() >= 3
    return bool(sides and grid[:4, 2:6].sum() <= 1)


def _alveolar_lateral(grid) -> bool:
    """The middle four columns of R1 or R2 touched (at least 3 of them) and the sides free
    behind (at most 2 electrodes in columns 1, 2, 7 and 8 of R3-R8)."""
    grid = np.asarray(grid).astype(bool)
    front = max(grid[0, 2:6].sum(), grid[1, 2:6].sum()) >= 3
    return bool(front and grid[2:, [0, 1, 6, 7]].sum() <= 2)


def _postalveolar_closure(grid) -> bool:
    """A complete row across R2 or R3 and contact along both sides."""
    grid = np.asarray(grid).astype(bool)
    return bool(grid[1:3].all(axis=1).any() and epg_classes.side_contact(grid))


def _rhotic_lateral(grid) -> bool:
    """Contact along both sides in the back rows (column 1 or 2, and 7 or 8, in at least three
    of R4-R8), none in R1-R2, and at most 2 electrodes of the middle four columns touched."""
    grid = np.asarray(grid).astype(bool)
    left = grid[3:, :2].any(axis=1).sum() >= 3
    right = grid[3:, 6:].any(axis=1).sum() >= 3
    return bool(left and right and not grid[:2].any() and grid[:, 2:6].sum() <= 2)


def _little_contact(grid) -> bool:
    return int(np.asarray(grid).sum()) <= 6


RULES = (
    (("T", "D", "N"), "complete closure across a front row with contact along both sides",
     lambda g: epg_classes.front_closure(g) and epg_classes.side_contact(g)),
    (("S", "Z"), "contact along the sides with a central groove open in the front rows",
     epg_classes.central_groove),
    (("K", "G"), "complete closure across a back row", epg_classes.back_closure),
    (("SH", "ZH"), "a groove wider than /s/'s and further back: sides touched in R2-R5, the "
                   "middle four columns free in R1-R4 (published descriptions)",
     _postalveolar_groove),
    (("L",), "the tip on the alveolar ridge (3 of the middle four columns of R1 or R2) with the "
             "sides free behind it (published descriptions)", _alveolar_lateral),
    (("CH", "JH"), "a complete closure across R2 or R3 with contact along both sides "
                   "(published descriptions)", _postalveolar_closure),
    (("IY",), "contact at the sides only (outer columns in most rows, at most 2 of the middle "
              "four columns' electrodes)", _sides_only),
    (("R",), "contact along both sides of the back rows (R4-R8), none in R1-R2 and at most 2 "
              "electrodes in the middle four columns (published descriptions)", _rhotic_lateral),
    (("AA",), "little or no contact (at most 6 electrodes)", _little_contact),
)


def _grid(rows) -> np.ndarray:
    return np.array([[int(c) for c in r] for r in rows], dtype=np.uint8)


def realism(grids: dict, classes: dict, before: dict | None = None) -> dict:
    """The rules per phoneme, and each EPG class's agreement with its phonemes' patterns;
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


def before_grids(targets: list[dict]) -> dict:
    """The 2D fits' grids of the contact-fitted targets' own (main) shapes, by symbol."""
    out = {}
    for t in targets:
        contact = t["source"].get("contact")
        if contact:
            out[t["arpabet"]] = _grid(contact["before"]["rows"])
    return out
