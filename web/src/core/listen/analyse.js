// The streaming analyser: samples in, one set of measures per 10 ms hop out. It runs where the
// microphone's samples arrive (an AudioWorklet's 128-sample quanta, or a worker) and over whole
// recordings (analyseSamples, `npm run measure`), with the same results either way: each hop is
// computed from the samples around it alone, once they have all arrived, never from how they
// were chunked.
//
//   const analyser = createAnalyser( { sampleRate: 48000, group: 'child' } );
//   for ( const hop of analyser.push( quantum ) ) show( hop );   // every quantum
//   analyser.flush();                                             // at the end: the last hops
//
// Hop k is centred at t = k * HOP_S s, and is complete once the longest analysis window around
// it has arrived and the pitch tracker has seen PITCH_LOOKAHEAD_HOPS more (analyser.latencyS
// after t). Each hop:
//   t             s
//   f0            Hz, YIN's candidates (pitch.js) tracked (pitchTrack.js); null when unvoiced
//   voiced        boolean
//   intensity_db  dB re 2e-5 Pa, samples taken as pascals (intensity.js); null in digital silence
//   formants      [ F1, F2, F3, F4 ] Hz, Burg LPC (lpc.js); null where fewer were found
//   bandwidths    [ B1, B2, B3, B4 ] Hz, likewise
//   centroid, spread (Hz), skew, peak (Hz): spectral moments over the band (moments.js); null
//                 in silence
//   f3_minus_f2   Hz (low for /r/); null without both
// Frames reaching before the first sample, or (after flush) past the last, read zeros there.

import { SampleStream, centreSample, windowStart } from './frames.js';
import { intensityDb, intensityWindow } from './intensity.js';
import { analyseFormants, createFormantAnalysis, lpcSpectrumDb } from './lpc.js';
import {
	MOMENT_CENTROID, MOMENT_PEAK, MOMENT_SKEW, MOMENT_SPREAD, analyseMoments, createMomentsAnalysis,
} from './moments.js';
import {
	DEFAULT_GROUP, FORMANTS_REPORTED, GROUPS, HOP_S, MOMENTS_WINDOW_S, PITCH_LOOKAHEAD_HOPS, VOICING_FLOOR_DB,
} from './params.js';
import { createYin, yinCandidates } from './pitch.js';
import { addPitchFrame, createPitchTracker, decidePitch } from './pitchTrack.js';
import { createResampler, firstInputFor, lastInputFor, resampleStream } from './resample.js';

const HOPS_PER_SECOND = Math.round( 1 / HOP_S );
const NO_HOPS = Object.freeze( [] );

/** How far a window of `length` centred on a sample reaches before it and after it. */
const reach = ( length ) => ( { before: Math.floor( length / 2 ), after: length - Math.floor( length / 2 ) } );

const finite = ( v ) => ( Number.isFinite( v ) ? v : null );

/**
 * A streaming analyser.
 * @param {{ sampleRate: number, group?: 'child' | 'woman' | 'man', band?: [ number, number ] }} options
 *   sampleRate: integer Hz (8000 or more); group: the speaker group (GROUPS in params.js),
 *   DEFAULT_GROUP when left out; band: the spectral moments' band in Hz (0 to Nyquist by default)
 * @returns {{ push: ( samples: Float32Array ) => object[], flush: () => object[],
 *   lpcSpectrum: ( target: Float32Array | Float64Array, maxHz?: number ) => typeof target,
 *   sampleRate: number, group: string, narrowRate: number, latencyS: number }}
 */
export function createAnalyser( { sampleRate, group = DEFAULT_GROUP, band } = {} ) {

	if ( ! Number.isInteger( sampleRate ) || sampleRate < 8000 ) throw new RangeError( `sample rate must be a whole number of Hz, 8000 or more, got ${ sampleRate }` );
	const settings = Object.hasOwn( GROUPS, group ) ? GROUPS[ group ] : null;
	if ( ! settings ) throw new RangeError( `unknown speaker group "${ group }" (one of ${ Object.keys( GROUPS ).join( ', ' ) })` );

	// Two streams: the input, for intensity and the spectral moments (which want its whole band),
	// and the input resampled to twice the formant ceiling, for the formants (as Praat) and the
	// pitch (which needs no more, and costs the same whatever the microphone's rate).
	const narrowRate = 2 * settings.formantCeiling;
	const resampler = narrowRate === sampleRate ? null : createResampler( sampleRate, narrowRate );
	const yin = createYin( { sampleRate: narrowRate, floor: settings.pitchFloor, ceiling: settings.pitchCeiling } );
	const formants = createFormantAnalysis( { sampleRate: narrowRate } );
	const loudness = intensityWindow( sampleRate, settings.pitchFloor );
	const moments = createMomentsAnalysis( { sampleRate, windowS: MOMENTS_WINDOW_S, band } );

	const loudReach = reach( loudness.length ), momentReach = reach( moments.frameLength );
	const inputBefore = Math.max( loudReach.before, momentReach.before );
	const inputAfter = Math.max( loudReach.after, momentReach.after );
	const pitchReach = reach( yin.frameLength ), formantReach = reach( formants.frameLength );
	const narrowBefore = Math.max( pitchReach.before, formantReach.before + 1 ); // + 1: the pre-emphasis reads one more
	const narrowAfter = Math.max( pitchReach.after, formantReach.after );

	// The input's lead of zeros covers every window reaching before the start (the narrow ones
	// too when no resampling is needed and the narrow stream is the input) and the resampler's reach.
	const input = new SampleStream( Math.max( inputBefore, resampler ? resampler.halfTaps : narrowBefore ) + 1 );
	const narrow = resampler ? new SampleStream( narrowBefore + 1 ) : input;
	const tracker = createPitchTracker( { candidates: yin.maxCandidates, lookahead: PITCH_LOOKAHEAD_HOPS, floor: settings.pitchFloor } );
	const pending = []; // hops analysed, waiting for their pitch to be decided
	let next = 0; // the next hop to analyse
	let received = 0;
	let finished = false;

	const inputCentre = ( k ) => centreSample( k / HOPS_PER_SECOND, sampleRate );
	const narrowCentre = ( k ) => centreSample( k / HOPS_PER_SECOND, narrowRate );

	function ready( k ) {

		return inputCentre( k ) + inputAfter <= input.end && narrowCentre( k ) + narrowAfter <= narrow.end;

	}

	function analyseHop( k ) {

		const c = inputCentre( k ), n = narrowCentre( k );
		const db = intensityDb( input.data, input.offset( windowStart( c, loudness.length ) ), loudness );
		const candidates = yinCandidates( yin, narrow.data, narrow.offset( windowStart( n, yin.frameLength ) ) );
		addPitchFrame( tracker, yin.candidateF0, yin.candidateAperiodicity, candidates, db !== null && db >= VOICING_FLOOR_DB );
		const m = analyseMoments( moments, input.data, input.offset( windowStart( c, moments.frameLength ) ) );
		const count = analyseFormants( formants, narrow.data, narrow.offset( windowStart( n, formants.frameLength ) ) );
		const frequencies = new Array( FORMANTS_REPORTED ).fill( null );
		const bandwidths = new Array( FORMANTS_REPORTED ).fill( null );
		for ( let i = 0; i < Math.min( count, FORMANTS_REPORTED ); i ++ ) {

			frequencies[ i ] = formants.frequencies[ i ];
			bandwidths[ i ] = formants.bandwidths[ i ];

		}

		return {
			t: k / HOPS_PER_SECOND,
			f0: null, // decided by the tracker, PITCH_LOOKAHEAD_HOPS later
			voiced: false,
			intensity_db: db,
			formants: frequencies,
			bandwidths,
			centroid: finite( m[ MOMENT_CENTROID ] ),
			spread: finite( m[ MOMENT_SPREAD ] ),
			skew: finite( m[ MOMENT_SKEW ] ),
			peak: finite( m[ MOMENT_PEAK ] ),
			f3_minus_f2: frequencies[ 1 ] !== null && frequencies[ 2 ] !== null ? frequencies[ 2 ] - frequencies[ 1 ] : null,
		};

	}

	/** Give the waiting hops whose pitch can be decided (all of them at the end) their pitch. */
	function decided( hops, all ) {

		while ( pending.length && ( all || tracker.frames > pending[ 0 ].index + PITCH_LOOKAHEAD_HOPS ) ) {

			const { hop, index } = pending.shift();
			const f0 = decidePitch( tracker, index );
			hop.f0 = f0 > 0 ? f0 : null;
			hop.voiced = f0 > 0;
			hops.push( hop );

		}

		return hops;

	}

	/** Analyse every complete hop before `limit`, then forget the samples no later hop reads. */
	function drain( limit, all = false ) {

		// Most quanta complete no hop: they return the one empty array, allocating nothing.
		if ( ! all && ! ( next < limit && ready( next ) ) ) return NO_HOPS;
		const hops = [];
		while ( next < limit && ready( next ) ) {

			pending.push( { hop: analyseHop( next ), index: next } );
			next ++;
			decided( hops, false );

		}

		decided( hops, all );
		let keepInput = inputCentre( next ) - inputBefore;
		if ( resampler ) {

			keepInput = Math.min( keepInput, firstInputFor( resampler, resampler.next ) );
			narrow.discardBefore( narrowCentre( next ) - narrowBefore );

		} else keepInput = Math.min( keepInput, narrowCentre( next ) - narrowBefore );
		input.discardBefore( keepInput );
		return hops;

	}

	/**
	 * Take the next samples (any length; a Float32Array or Float64Array); returns the hops
	 * completed (when none, one shared, frozen empty array).
	 */
	function push( samples ) {

		if ( finished ) throw new Error( 'this analyser was flushed; create another for more samples' );
		input.append( samples );
		received += samples.length;
		if ( resampler ) resampleStream( resampler, input, narrow );
		return drain( Infinity );

	}

	/** The signal has ended: complete every hop up to its duration (zeros after it); returns them. */
	function flush() {

		if ( finished ) return [];
		finished = true;
		const last = Math.floor( received * HOPS_PER_SECOND / sampleRate + 1e-9 );
		let needed = inputCentre( last ) + inputAfter;
		if ( resampler ) needed = Math.max( needed, lastInputFor( resampler, narrowCentre( last ) + narrowAfter - 1 ) + 1 );
		else needed = Math.max( needed, narrowCentre( last ) + narrowAfter );
		if ( needed > input.end ) input.appendZeros( needed - input.end );
		if ( resampler ) resampleStream( resampler, input, narrow );
		return drain( last + 1, true );

	}

	/**
	 * The LPC spectrum (dB; lpc.js lpcSpectrumDb), 0 to maxHz (the ceiling), of the newest hop
	 * analysed: the one PITCH_LOOKAHEAD_HOPS after the last returned, whose pitch is not decided yet.
	 */
	function lpcSpectrum( target, maxHz = settings.formantCeiling ) {

		return lpcSpectrumDb( formants.a, formants.order, formants.gain2, narrowRate, target, maxHz );

	}

	const latencyS = PITCH_LOOKAHEAD_HOPS * HOP_S + Math.max( inputAfter / sampleRate, narrowAfter / narrowRate + ( resampler ? resampler.halfTaps / sampleRate : 0 ) );
	return { push, flush, lpcSpectrum, sampleRate, group, narrowRate, latencyS };

}

/**
 * Every hop of a whole recording: hops at 0, HOP_S, ... up to its duration.
 * @param {Float32Array} samples mono
 * @param {number} sampleRate Hz
 * @param {{ group?: string, band?: [ number, number ] }} [options]
 * @returns {object[]} the hops (see createAnalyser)
 */
export function analyseSamples( samples, sampleRate, { group = DEFAULT_GROUP, band } = {} ) {

	const analyser = createAnalyser( { sampleRate, group, band } );
	return [ ...analyser.push( samples ), ...analyser.flush() ];

}
