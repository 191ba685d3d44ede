"""Examples in the OpenAPI document that more than one route shows (a route imports no other
route, so they live here)."""

#: The documented example: two frames, 5 ms apart, of the /s/ -> /k/ of "bescan" in the emuR
#: reference data (utterance sp1bescan), as the emuR JSON format writes them.
EMUR_EXAMPLE = {"segments": [{
    "label": "s->k", "utt": "sp1bescan", "word": "bescan", "start_ms": 156095.0,
    "end_ms": 156100.0, "frames": [
        {"t_ms": 156095.0, "rows": ["01100010", "11100011", "11100001", "11000001", "11000001",
                                    "11000001", "11000011", "11100011"]},
        {"t_ms": 156100.0, "rows": ["01000010", "11100011", "11100001", "11000001", "11000001",
                                    "11000001", "11000011", "11100111"]}]}]}
