"""The mapping from VocalTractLab's articulatory settings onto the rigs' parameters.

VocalTractLab's JD3 speaker (its stored shapes, read by ``pipeline.vtl_speaker``, and the states
of its gestural model, read by ``training.vtl_reference``) is set by 19 tract parameters; the
rigs have their own. What the fits cannot take from a tongue outline or surface is carried
across here, one rule per rig parameter (``MAPPING_TEXT``, written into the phoneme targets):

- the jaw from JA (``jaw_opening``): each model's rest counted as 0; a mapping of intent, not of
  geometry, since the two jaws pivot at different places;
- the lips from LP, LD and JX (``lips_from_vtl``);
- the coronal edge heights from the side elevations TS1-TS3 (``coronal_from_vtl``);
- the velum: lowered for the nasals, raised otherwise (``velum_of``), or, for the gestural
  model's states, from its velic opening VO (``velum_from_vo``).

The phoneme targets (the build), the mid-sagittal and 3D fits of VTL's shapes and the
coarticulation trainer all read these, so they map a shape alike.
"""

import numpy as np
import numpy.typing as npt

from glasshead.geometry.tongue_surface import TongueRig

#: JD3's jaw angle at rest (VTL's "standard" JA), degrees.
VTL_JA_REST = -2.0
#: mm. JD3's lip protrusion LP in its unrounded shapes (/a/ 0.72, /i/ 0.77, /t/(a) 0.72): the
#: lips at rest, counted as no protrusion.
VTL_LP_REST_MM = 0.7
#: mm of lip_rounding per mm of LP beyond rest (VTL has no separate rounding: its rounded vowels
#: are protruded and narrowed together).
ROUNDING_PER_LP_MM = 1.0
#: mm. JD3 moves its jaw back (JX) by 5 mm in its labiodental shapes to bring the lower lip under
#: the upper incisors; the rig tucks the lower lip instead. JX within this of 0 (the vowels go
#: to -2) counts as no tuck; from there to -5 the tuck grows to its maximum.
VTL_JX_TUCK_START_MM = 2.0
VTL_JX_TUCK_FULL_MM = 5.0
#: The face rig's lip gap (mm) with the lips open at jaw openings (deg), as measured on the
#: built rig (docs/face-rig.md, "Measured"): lip_opening = LD / gap at the target's jaw.
RIG_LIP_GAP = ((0.0, 1.0), (5.0, 7.8), (10.0, 13.9), (15.0, 19.6), (20.0, 24.7), (25.0, 29.4))
#: Coronal section -> VTL side elevation parameter.
SIDE_ELEVATION = (("front", "TS3"), ("middle", "TS2"), ("back", "TS1"))
#: cm^2: VTL's velum opening VO when closed (its rest) and at a nasal's velic gesture. The
#: stored shapes all hold it closed, so the targets set the velum by nasality instead.
VO_CLOSED = -0.1
VO_NASAL = 0.5

MAPPING_TEXT = {
    "jaw": "jaw_opening = -2 - JA (deg), JD3's standard JA being -2 deg and negative opening, "
           "clipped to the rig's range (fit2d.jaw_opening_from_vtl)",
    "lip_opening": "0 when LD <= 0 (VTL's lips closed or pressed); otherwise LD divided by the "
                   "rig's open-lip gap at the target's jaw opening, clipped to 0..1",
    "lip_protrusion": f"LP - {VTL_LP_REST_MM} mm, clipped to the rig's range",
    "lip_rounding": f"{ROUNDING_PER_LP_MM} x (LP - {VTL_LP_REST_MM} mm), clipped: protruded "
                    "lips are rounded, retracted ones spread",
    "upper_lip_raise": "0 (VTL has no such parameter)",
    "lower_lip_tuck": f"from VTL's jaw retraction JX: 0 down to -{VTL_JX_TUCK_START_MM} mm, "
                      f"growing linearly to the rig's maximum at -{VTL_JX_TUCK_FULL_MM} mm",
    "velum_opening": "1 (lowered) for the nasals /m n ŋ/, 0 (raised) for every other phoneme",
    "coronal": "edge heights (left and right alike) from VTL's side elevations: front from TS3, "
               "middle from TS2, back from TS1, mm, clipped; other coronal parameters neutral",
}


def clip(spec: dict, value: float) -> float:
    """``value`` within a parameter's range (``spec``: its ``min`` and ``max``)."""
    return float(np.clip(value, spec["min"], spec["max"]))


def jaw_opening(ja: npt.ArrayLike, spec: dict) -> np.ndarray:
    """The rig's jaw_opening (deg) for VTL jaw angles JA (deg, a value or (n,)): opening =
    VTL_JA_REST - JA (JD3's JA is negative when open), clipped to the rig's range ``spec``."""
    return np.clip(VTL_JA_REST - np.asarray(ja, dtype=np.float64), spec["min"], spec["max"])


def jaw_opening_from_vtl(shape: dict, rig: TongueRig) -> float:
    """The rig's jaw_opening (deg) for a VTL shape record's jaw angle JA (``jaw_opening``)."""
    angle = float(shape["settings"]["jaw"]["JA"])
    return float(jaw_opening(angle, rig.parameters[rig.jaw["parameter"]]))


def _interp_gap(jaw_deg: float) -> float:
    xs, ys = zip(*RIG_LIP_GAP, strict=True)
    return float(np.interp(jaw_deg, xs, ys))


def lips_from_vtl(settings: dict, jaw_opening: float, lip_table: dict) -> dict:
    """The face rig's lip parameters for a VTL shape's settings (lengths in mm; see
    ``MAPPING_TEXT``) at the target's jaw opening; ``lip_table``: the face rig's parameters by
    name."""
    lp, ld = settings["lips"]["LP"], settings["lips"]["LD"]
    jx = settings["jaw"]["JX"]
    opening = 0.0 if ld <= 0 else ld / _interp_gap(jaw_opening)
    tuck_share = (-jx - VTL_JX_TUCK_START_MM) / (VTL_JX_TUCK_FULL_MM - VTL_JX_TUCK_START_MM)
    tuck_spec = lip_table["lower_lip_tuck"]
    return {
        "lip_opening": clip(lip_table["lip_opening"], opening),
        "lip_rounding": clip(lip_table["lip_rounding"],
                             ROUNDING_PER_LP_MM * (lp - VTL_LP_REST_MM)),
        "lip_protrusion": clip(lip_table["lip_protrusion"], lp - VTL_LP_REST_MM),
        "upper_lip_raise": clip(lip_table["upper_lip_raise"], 0.0),
        "lower_lip_tuck": clip(tuck_spec, tuck_spec["min"] + float(np.clip(tuck_share, 0, 1))
                               * (tuck_spec["max"] - tuck_spec["min"])),
    }


def coronal_from_vtl(rig: TongueRig, settings: dict, edge_range: tuple[float, float]) -> dict:
    """Edge heights (mm) from VTL's side elevations (see ``MAPPING_TEXT``), left and right
    alike, clipped to ``edge_range`` (which lies within the rig's)."""
    values = {}
    for section, name in SIDE_ELEVATION:
        for side in ("left", "right"):
            parameter = f"{section}_{side}_edge_height"
            if parameter in rig.parameters:
                values[parameter] = float(np.clip(float(settings["tongue"][name]), *edge_range))
    return values


def velum_of(nasal: bool, spec: dict) -> float:
    """The velum of a phoneme: lowered (the range's maximum) for a nasal, raised otherwise."""
    return float(spec["max"] if nasal else spec["min"])


def velum_from_vo(vo: npt.ArrayLike, spec: dict) -> np.ndarray:
    """The velum (``spec``'s range) for VTL velic openings VO (cm^2): VO_CLOSED to VO_NASAL onto
    the range, clipped; at a nasal's velic target it gives what ``velum_of`` gives a nasal."""
    share = np.clip((np.asarray(vo, dtype=np.float64) - VO_CLOSED) / (VO_NASAL - VO_CLOSED),
                    0.0, 1.0)
    return spec["min"] + share * (spec["max"] - spec["min"])
