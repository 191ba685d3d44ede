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

#: One frame of flesh points (fit kind ``ema``, or a combined fit's ``ema_file``): the sensors
#: of the head's /t/, mm in the project frame.
FLESH_POINTS_EXAMPLE = """point,x_mm,y_mm,z_mm
tongue_tip,17.4,11.7,0
tongue_blade,0.7,12.6,0
tongue_dorsum,-16.1,16.7,0
lower_incisor,24.8,-6.6,0
upper_lip,37.1,-2.6,0
lower_lip,33.3,-5.4,0
"""
