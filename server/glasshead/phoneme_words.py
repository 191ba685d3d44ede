"""How each phoneme is made, in a teacher's words: what the lips, the teeth, the tongue, the soft
palate and the voice do, as a teacher says it to a class and an author reads it beside a target.
Written from the phonetics of each sound (place, manner, voicing; the vowel's height, backness
and rounding), in plain words, one or two sentences each; ``GET /phonemes`` serves them as
``how``."""

#: ARPAbet -> how the sound is made, for every phoneme of ``glasshead.phonemes.INVENTORY``.
HOW_IT_IS_MADE: dict[str, str] = {
    # Vowels: the voice is on for all of them; the mouth's shape makes the difference.
    "AA": "Open the mouth wide and let the tongue lie low and pulled back, lips relaxed, voice "
          "on: the 'ah' a doctor asks for.",
    "AE": "Open the mouth and spread the lips a little, the tongue low and forward, voice on: "
          "the 'a' in cat.",
    "AH": "Mouth half open, the tongue relaxed in the middle of the mouth, voice on: a short "
          "'uh'.",
    "AO": "Mouth open and lips rounded, the tongue low at the back, voice on: the 'aw' in law.",
    "EH": "Mouth half open, lips relaxed, the front of the tongue half raised, voice on: the 'e' "
          "in bed.",
    "ER": "Lips a little rounded and the body of the tongue bunched up in the middle of the "
          "mouth, not touching the roof, voice on: the 'er' in bird.",
    "IH": "Lips slightly spread, the front of the tongue high but relaxed, voice on: the short "
          "'i' in sit.",
    "IY": "Smile: lips spread, the front of the tongue raised high near the roof of the mouth, "
          "voice on: 'ee'.",
    "UH": "Lips loosely rounded, the back of the tongue raised but relaxed, voice on: the 'oo' "
          "in book.",
    "UW": "Lips tightly rounded and pushed forward, the back of the tongue raised high, voice "
          "on: the 'oo' in boot.",
    "AW": "Start with the mouth wide open as for 'ah', then close and round the lips toward "
          "'oo': 'ow'.",
    "AY": "Start wide open as for 'ah', then raise the tongue and spread the lips toward 'ee': "
          "'eye'.",
    "EY": "Start with the mouth half open as for 'e', then close it toward 'ee': the 'ay' in "
          "day.",
    "OW": "Start with rounded lips as for 'o', then round them more toward 'oo': the 'oh' in go.",
    "OY": "Start with rounded lips as for 'aw', then spread them and raise the tongue toward "
          "'ee': the 'oy' in boy.",
    # Consonants: where the air is stopped or squeezed, how, and whether the voice is on.
    "P": "Close the lips, let the air build up behind them, then open them with a little pop of "
         "air. No voice.",
    "B": "Close the lips and open them with a soft pop, the voice on from the start.",
    "M": "Close the lips and hum: the voice comes out through the nose.",
    "F": "Rest the upper teeth lightly on the lower lip and blow a steady stream of air. No "
         "voice.",
    "V": "Upper teeth on the lower lip as for 'f', and add the voice: it buzzes.",
    "TH": "Put the tip of the tongue just between the teeth and blow air over it. No voice.",
    "DH": "The tip of the tongue between the teeth as for 'th' in thin, with the voice on.",
    "T": "Press the tip of the tongue on the ridge behind the upper teeth, then let it go with a "
         "little puff of air. No voice.",
    "D": "The tip of the tongue on the ridge behind the upper teeth, let go with the voice on.",
    "N": "The tip of the tongue on the ridge behind the upper teeth, and hum: the voice goes out "
         "through the nose.",
    "S": "The tip of the tongue close to the ridge behind the upper teeth, teeth nearly "
         "together: blow a thin stream of air along a groove in the tongue, a hiss. No voice.",
    "Z": "As for 's', with the voice on: a buzz.",
    "L": "The tip of the tongue on the ridge behind the upper teeth, its sides down, so the "
         "voice flows out round them.",
    "SH": "Lips pushed forward, the tongue a little further back and wider than for 's': blow a "
          "soft rushing air, 'shh'. No voice.",
    "ZH": "As for 'shh', with the voice on: the sound in the middle of 'measure'.",
    "CH": "The tongue against the roof just behind the ridge, lips forward, then let go into "
          "'shh': 'ch'. No voice.",
    "JH": "As for 'ch', with the voice on: the 'j' in jump.",
    "Y": "Raise the front of the tongue close to the roof of the mouth as for 'ee', then glide "
         "into the next vowel: the 'y' in yes.",
    "K": "Raise the back of the tongue against the soft palate, then let it go with a puff of "
         "air. No voice.",
    "G": "The back of the tongue against the soft palate, let go with the voice on.",
    "NG": "The back of the tongue against the soft palate, and hum: the voice goes out through "
          "the nose, as at the end of 'sing'.",
    "W": "Round the lips tightly as for 'oo' and raise the back of the tongue, then glide into "
         "the next vowel.",
    "R": "Bunch the tongue up and back without touching the roof of the mouth, lips a little "
         "rounded, voice on.",
    "HH": "Open the mouth for the next vowel and breathe out through it: a quiet puff from the "
          "throat. No voice.",
}


def how_it_is_made(arpabet: str) -> str:
    """How the phoneme ``arpabet`` is made, in a teacher's words."""
    return HOW_IT_IS_MADE[arpabet]
