// The listening kernels' analysis parameters, in one place, each with its reason.
//
// Times are in seconds, frequencies in hertz. Where a value follows Praat, it is Praat's default
// for the same analysis (Boersma & Weenink, Praat: doing phonetics by computer), so that our
// measures can be checked against Praat's.

/** Time between analysis frames (s): 100 frames a second, as Praat's default for speech tracks. */
export const HOP_S = 0.01;

/**
 * Speaker groups: the pitch range searched (Hz) and the formant ceiling (Hz) of the Burg
 * analysis. Ceilings are Praat's advice for men (5000) and women (5500); children's shorter
 * tracts put their formants higher (Hillenbrand et al. 1995 measured F3 of 10-12 year olds near
 * 3,200 Hz against 2,500 for men), hence 6500. The pitch ranges cover the /hVd/ vowels of
 * Hillenbrand et al. (1995) (men 91-189 Hz, women 166-272, children 183-294 at the steady state)
 * with room for intonation.
 */
export const GROUPS = Object.freeze( {
	child: Object.freeze( { pitchFloor: 150, pitchCeiling: 500, formantCeiling: 6500 } ),
	woman: Object.freeze( { pitchFloor: 120, pitchCeiling: 400, formantCeiling: 5500 } ),
	man: Object.freeze( { pitchFloor: 60, pitchCeiling: 250, formantCeiling: 5000 } ),
} );

/** The group analysed when none is named. */
export const DEFAULT_GROUP = 'woman';

/** Formants sought: 5, i.e. an LPC of order 2 x 5 = 10 (Praat's "To Formant (burg)"). */
export const FORMANT_COUNT = 5;

/** Formants reported per frame (F1..F4). */
export const FORMANTS_REPORTED = 4;

/**
 * Praat's formant "window length" (s). As in Praat, the Gaussian window actually spans twice
 * this (50 ms); its effective length (where it is above half its height) is about this.
 */
export const FORMANT_WINDOW_S = 0.025;

/** Pre-emphasis from this frequency (Hz) up, +6 dB per octave (Praat's default). */
export const PREEMPHASIS_FROM_HZ = 50;

/** Roots closer than this (Hz) to 0 or to the ceiling are not formants (Praat's safety margin). */
export const FORMANT_MARGIN_HZ = 50;

/**
 * Intensity window, in periods of the pitch floor: Praat's 3.2 (long enough that the pitch
 * periods do not show as ripple); the Kaiser window spans twice this.
 */
export const INTENSITY_PERIODS = 3.2;

/**
 * Intensity is in dB re 2e-5 Pa with the samples taken as pascals, as Praat does: a full-scale
 * sine (amplitude 1) reads 91 dB. Subtract FULL_SCALE_DB to get dB re full scale (dBFS, where
 * an RMS of 1 is 0 dB). Microphones are not calibrated, so only differences are meaningful.
 */
export const REFERENCE_PRESSURE_PA = 2e-5;

/** 20 log10( 1 / 2e-5 ): the intensity of a signal of RMS 1 (about 93.98 dB). */
export const FULL_SCALE_DB = 20 * Math.log10( 1 / REFERENCE_PRESSURE_PA );

/**
 * YIN's absolute threshold on the cumulative mean normalised difference (de Cheveigné &
 * Kawahara 2002, step 4; 0.1 as in the paper): in yinPitch(), YIN's own one-frame choice, the
 * first dip below it is the period. The analyser uses the tracker instead.
 */
export const YIN_THRESHOLD = 0.1;

/** Dips of YIN's d' kept per frame as pitch candidates for the tracker. */
export const PITCH_CANDIDATES = 6;

/**
 * The pitch tracker's costs (pitchTrack.js), Praat's defaults for "To Pitch (ac)" carried over,
 * YIN's d' playing the part of 1 - Praat's correlation strength. Octave cost: per octave, favours
 * the higher of candidates that are equally periodic (a periodic signal repeats at 2T too).
 * Praat's is 0.01; d' leans to the undertone more than Praat's correlation does, and on
 * Hillenbrand's vowels 0.02 removed the last octave errors at the steady states where 0.04
 * began to make octave-up errors.
 */
export const OCTAVE_COST = 0.02;
/** Per octave of pitch change from one frame to the next: resists octave jumps. */
export const OCTAVE_JUMP_COST = 0.35;
/** Per switch between voiced and unvoiced: resists flicker at the edges of voicing. */
export const VOICED_UNVOICED_COST = 0.14;
/** Praat's voicing threshold: a frame is locally voiced when its best d' is below 1 - this. */
export const VOICING_STRENGTH = 0.45;

/** Frames of lookahead before a frame's pitch is decided live (10 ms each): the tracker's latency. */
export const PITCH_LOOKAHEAD_HOPS = 5;

/** No voicing below this intensity (dB re 2e-5 Pa, about -64 dBFS): background hiss, not a voice. */
export const VOICING_FLOOR_DB = 30;

/** Spectral moments window (s): 20 ms, as Forrest et al. (1988). */
export const MOMENTS_WINDOW_S = 0.02;
