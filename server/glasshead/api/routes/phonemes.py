"""GET /phonemes: the articulation target of every phoneme; GET /phonemes/{symbol}: one of them.

Built by `glasshead build` (``pipeline.phoneme_targets``, docs/targets.md) and read through the
asset store; a symbol is ARPAbet (any case, a stress digit allowed) or IPA, as
``glasshead.phonemes.lookup`` takes it.
"""

from fastapi import APIRouter, HTTPException
from pydantic import BaseModel, ConfigDict, Field

from glasshead.api.deps import AssetsDep
from glasshead.phoneme_words import how_it_is_made
from glasshead.phonemes import UnknownPhonemeError, lookup

router = APIRouter(tags=["phonemes"])


class SourceSummary(BaseModel):
    model_config = ConfigDict(extra="allow")

    kind: str = Field(description="fit, fit, adjusted or reasoning")
    shapes: list[str] = Field(default_factory=list, description="the JD3 shapes fitted")
    rms_mm: float | None = Field(default=None, description="the main shape's fit RMS error")


class PhonemeSummary(BaseModel):
    arpabet: str
    ipa: str
    kind: str = Field(description="vowel, diphthong or consonant")
    voiced: bool = Field(description="whether the folds vibrate (the glottis is held open when "
                                     "not)")
    manner: str = Field(description="consonants: stop, fricative, affricate, nasal, lateral, "
                                    "approximant; vowels: their height")
    examples: list[str]
    how: str = Field(description="how the sound is made, in a teacher's words")
    source: SourceSummary
    epg_basis: str = Field(description="what the palatogram was fitted to: real EPG, published "
                                       "descriptions, or not fitted")
    url: str


class PhonemeList(BaseModel):
    format_version: int
    count: int
    phonemes: list[PhonemeSummary]


class EpgPattern(BaseModel):
    rows: list[str] = Field(description="8 strings of '0'/'1', R1 (front) first; character c = "
                                        "column c + 1")
    indices: dict[str, float] = Field(description="emuR indices of the pattern")


class PhonemeTarget(BaseModel):
    model_config = ConfigDict(extra="allow")

    arpabet: str
    ipa: str
    kind: str
    examples: list[str]
    how: str = Field(description="how the sound is made, in a teacher's words")
    features: dict
    velum: str = Field(description="lowered (nasals) or raised")
    params: dict[str, float] = Field(description="every parameter of the tongue, face (lips) "
                                                 "and velum rigs")
    contexts: dict = Field(description="measured consonants: the target in /a/, /i/ and /u/ "
                                       "context (params, fit, volume, epg)")
    source: dict = Field(description="the JD3 shape(s) and fit error, or the reasoning")
    volume_change_pct: float = Field(description="the tongue's volume against rest, percent")
    epg_basis: str = Field(description="what the palatogram was fitted to: real EPG (the "
                                       "engassim frames of its class), published descriptions, "
                                       "or not fitted (the outline fit's contacts)")
    epg: EpgPattern


def _targets(assets) -> dict:
    return assets.get("phoneme_targets")


def _summary(target: dict) -> dict:
    source = target["source"]
    features = target["features"]
    return {"arpabet": target["arpabet"], "ipa": target["ipa"], "kind": target["kind"],
            "voiced": features["voiced"], "manner": features["manner"],
            "examples": target["examples"], "how": how_it_is_made(target["arpabet"]),
            "source": {"kind": source.get("kind"), "shapes": source.get("shapes", []),
                       "rms_mm": source.get("rms_mm")},
            "epg_basis": target["epg_basis"],
            "url": f"/api/v1/phonemes/{target['arpabet']}"}


@router.get("/phonemes", operation_id="listPhonemes", response_model=PhonemeList)
def list_phonemes(assets: AssetsDep) -> dict:
    """Every phoneme of the inventory with its IPA, kind, examples and where its target comes
    from."""
    document = _targets(assets)
    return {"format_version": document["format_version"], "count": len(document["targets"]),
            "phonemes": [_summary(t) for t in document["targets"]]}


@router.get("/phonemes/{symbol}", operation_id="getPhoneme", response_model=PhonemeTarget)
def get_phoneme(symbol: str, assets: AssetsDep) -> dict:
    """One phoneme's target: ARPAbet (any case, stress digit allowed) or IPA (URL-encoded)."""
    document = _targets(assets)
    try:
        phoneme = lookup(symbol)
    except UnknownPhonemeError as exc:
        raise HTTPException(status_code=404, detail=(
            f"no phoneme {symbol!r}: {exc}; GET /api/v1/phonemes lists them")) from None
    for target in document["targets"]:
        if target["arpabet"] == phoneme.arpabet:
            return {**target, "how": how_it_is_made(target["arpabet"])}
    raise HTTPException(status_code=404, detail=(
        f"phoneme {symbol!r} ({phoneme.arpabet}) has no built target; "
        "GET /api/v1/phonemes lists them"))
