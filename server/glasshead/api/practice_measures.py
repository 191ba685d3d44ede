"""What the learner's voice measured on one go at an item (the listening page's summary of the
attempt, docs/listening.md), as a practice record keeps it: numbers and a verdict, never the
audio. Each field is optional, null or left out when not measured (a fricative has no formants,
a vowel no centroid), and bounded by what a human voice can give, so that a bad measurement is
refused by name, not stored."""

from typing import Annotated, Literal

from pydantic import BaseModel, ConfigDict, Field

#: Bounds of each measure, Hz or s: wide enough for any speaker, child to man.
F0 = Annotated[float, Field(ge=40, le=1500, description="median pitch over the vowel, Hz")]
F1 = Annotated[float, Field(ge=100, le=2500, description="median first formant, Hz")]
F2 = Annotated[float, Field(ge=300, le=5500, description="median second formant, Hz")]
F3 = Annotated[float, Field(ge=800, le=7000, description="median third formant, Hz")]
F3MinusF2 = Annotated[float, Field(ge=0, le=6000, description="F3 - F2, Hz (low for /r/)")]
Centroid = Annotated[float, Field(ge=100, le=24000,
                                  description="the fricative's spectral centroid, Hz")]
Duration = Annotated[float, Field(ge=0, le=60, description="how long the vowel (or the hiss) "
                                                           "lasted, s")]
VowelCode = Annotated[str, Field(pattern=r"^[a-z]{2}$", description="a vowel of "
                                                                     "vowel-norms.json")]


class AttemptMeasures(BaseModel):
    """The attempt's measures; ``verdict`` says whether it was in the target zone, near it, or
    off it, ``target_vowel`` which vowel's zone (a code of vowel-norms.json) when one was set."""

    model_config = ConfigDict(extra="forbid", json_schema_extra={"examples": [
        {"f0": 251.0, "f1": 410.0, "f2": 3050.0, "f3": 3600.0, "f3_minus_f2": 550.0,
         "duration_s": 0.26, "verdict": "in", "target_vowel": "iy"}]})
    f0: F0 | None = None
    f1: F1 | None = None
    f2: F2 | None = None
    f3: F3 | None = None
    f3_minus_f2: F3MinusF2 | None = None
    centroid: Centroid | None = None
    duration_s: Duration | None = None
    verdict: Literal["in", "near", "off"] | None = None
    target_vowel: VowelCode | None = None
