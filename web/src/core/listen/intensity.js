// Intensity of a frame in dB, as Praat's "To Intensity" computes it (Sound_to_Intensity.cpp): the
// mean of the squared samples under a Kaiser window of 2 x 3.2 periods of the pitch floor (long
// enough that single pitch periods do not show), after the window's plain mean is subtracted (so
// that a DC offset reads as silence). The samples are taken as pascals and the result is in dB
// re 2e-5 Pa (a full-scale sine reads 91 dB; see FULL_SCALE_DB in params.js for dBFS).

import { kaiserWindow } from './frames.js';
import { INTENSITY_PERIODS, REFERENCE_PRESSURE_PA } from './params.js';

/** Praat's Kaiser shape for the intensity window: 2 pi^2 + 0.5 (about 20). */
const KAISER_BETA = 2 * Math.PI * Math.PI + 0.5;
const REFERENCE_POWER = REFERENCE_PRESSURE_PA * REFERENCE_PRESSURE_PA;

/**
 * The intensity window for a pitch floor: 2 floor( 3.2 / floor * sampleRate ) + 1 samples.
 * @param {number} sampleRate Hz
 * @param {number} pitchFloor Hz
 * @returns {Float64Array}
 */
export function intensityWindow( sampleRate, pitchFloor ) {

	const half = Math.floor( INTENSITY_PERIODS / pitchFloor * sampleRate );
	return kaiserWindow( half, KAISER_BETA );

}

/**
 * Intensity (dB re 2e-5 Pa) of samples[ start .. start + window.length ) under `window`, or null
 * when the frame is digital silence. Allocates nothing.
 * @param {Float32Array | Float64Array} samples
 * @param {number} start index of the window's first sample
 * @param {Float64Array} window from intensityWindow()
 * @returns {number | null}
 */
export function intensityDb( samples, start, window ) {

	const n = window.length;
	let mean = 0;
	for ( let i = 0; i < n; i ++ ) mean += samples[ start + i ];
	mean /= n;
	let power = 0, weight = 0;
	for ( let i = 0; i < n; i ++ ) {

		const v = samples[ start + i ] - mean;
		power += v * v * window[ i ];
		weight += window[ i ];

	}

	power /= weight;
	// Below 1e-30 of the reference is rounding noise of a silent frame (Praat reads it as -300 dB).
	return power / REFERENCE_POWER < 1e-30 ? null : 10 * Math.log10( power / REFERENCE_POWER );

}
