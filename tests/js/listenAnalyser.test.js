// The streaming analyser (web/src/core/listen/analyse.js): the same hops whether a recording
// arrives at once or in AudioWorklet quanta of 128 samples (or any chunks), hops on the 10 ms
// grid up to the end, each out no later than its stated latency, its inputs checked, and per-hop
// kernels that allocate nothing.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { analyseSamples, createAnalyser } from '../../web/src/core/listen/analyse.js';
import { SampleStream } from '../../web/src/core/listen/frames.js';
import { intensityDb, intensityWindow } from '../../web/src/core/listen/intensity.js';
import { analyseFormants, createFormantAnalysis } from '../../web/src/core/listen/lpc.js';
import { analyseMoments, createMomentsAnalysis } from '../../web/src/core/listen/moments.js';
import { createYin, yinCandidates } from '../../web/src/core/listen/pitch.js';
import { addPitchFrame, createPitchTracker, decidePitch } from '../../web/src/core/listen/pitchTrack.js';
import { createResampler, resampleStream } from '../../web/src/core/listen/resample.js';
import { fewestGarbageCollections, garbageCollections } from './support/garbage.js';
import { noise, random, vowel } from './support/listenSignals.js';

const KEYS = [ 't', 'f0', 'voiced', 'intensity_db', 'formants', 'bandwidths', 'centroid', 'spread', 'skew', 'peak', 'f3_minus_f2' ];

/** Silence, a vowel, a fricative-like noise, another vowel: every measure changes somewhere. */
function utterance( sampleRate ) {

	const parts = [
		new Float32Array( Math.round( 0.12 * sampleRate ) ),
		vowel( { sampleRate, seconds: 0.3, f0: 210, formants: [ 800, 1300, 2700, 3600, 4600 ], bandwidths: [ 80, 100, 150, 200, 250 ] } ),
		noise( Math.round( 0.15 * sampleRate ), 5, 0.05 ),
		vowel( { sampleRate, seconds: 0.25, f0: 180, formants: [ 350, 2300, 3000, 3700, 4700 ], bandwidths: [ 60, 100, 150, 200, 250 ] } ),
	];
	const out = new Float32Array( parts.reduce( ( n, p ) => n + p.length, 0 ) );
	let at = 0;
	for ( const part of parts ) {

		out.set( part, at );
		at += part.length;

	}

	return out;

}

/** Feed `signal` in chunks of the sizes `sizes()` gives, then flush. */
function inChunks( signal, sampleRate, group, sizes ) {

	const analyser = createAnalyser( { sampleRate, group } );
	const hops = [];
	for ( let i = 0; i < signal.length; ) {

		const n = sizes();
		for ( const hop of analyser.push( signal.subarray( i, i + n ) ) ) hops.push( hop );
		i += n;

	}

	for ( const hop of analyser.flush() ) hops.push( hop );
	return hops;

}

test( 'the hops are the same whether the samples come at once or in quanta of 128', () => {

	// 11000 and 13000 Hz are a woman's and a child's formant rates: the path without resampling.
	for ( const [ sampleRate, group ] of [ [ 44100, 'woman' ], [ 16000, 'man' ], [ 48000, 'child' ], [ 11000, 'woman' ], [ 13000, 'child' ] ] ) {

		const signal = utterance( sampleRate );
		const whole = analyseSamples( signal, sampleRate, { group } );
		// Every number is a number: no window read outside the buffer.
		assert.ok( whole.every( ( h ) => [ h.intensity_db, h.centroid, ...h.formants ].every( ( v ) => v === null || Number.isFinite( v ) ) ) );
		assert.ok( whole[ 1 ].formants[ 0 ] === null || whole[ 1 ].formants[ 0 ] > 0 );
		assert.ok( whole.some( ( h ) => h.voiced ) && whole.some( ( h ) => ! h.voiced && h.intensity_db !== null ), 'the signal has voiced and unvoiced sound' );
		assert.deepStrictEqual( inChunks( signal, sampleRate, group, () => 128 ), whole, `${ sampleRate } Hz, ${ group }` );

	}

} );

test( 'the hops are the same in chunks of seeded random sizes, including empty and single samples', () => {

	const sampleRate = 22050, seed = 128;
	const signal = utterance( sampleRate );
	const next = random( seed );
	const sizes = () => [ 0, 1, 2, 127, 128, 129, 1000, 4096 ][ Math.floor( next() * 8 ) ];
	assert.deepStrictEqual( inChunks( signal, sampleRate, 'woman', sizes ), analyseSamples( signal, sampleRate ), `seed ${ seed }` );

} );

test( 'hops lie on the 10 ms grid from 0 to the end, with exactly the documented keys', () => {

	const sampleRate = 16000;
	const signal = utterance( sampleRate );
	const hops = analyseSamples( signal, sampleRate, { group: 'woman' } );
	assert.equal( hops.length, Math.floor( signal.length / sampleRate * 100 ) + 1 );
	hops.forEach( ( hop, k ) => {

		assert.equal( hop.t, k / 100 );
		assert.deepEqual( Object.keys( hop ), KEYS );
		assert.equal( hop.formants.length, 4 );
		assert.equal( hop.bandwidths.length, 4 );
		assert.equal( hop.voiced, hop.f0 !== null );

	} );

} );

test( 'each hop comes out no later than latencyS after its time, and no hop waits for flush() that need not', () => {

	const sampleRate = 44100;
	const signal = utterance( sampleRate );
	const analyser = createAnalyser( { sampleRate, group: 'man' } );
	assert.ok( analyser.latencyS > 0.05 && analyser.latencyS < 0.15, `latency ${ analyser.latencyS } s` );
	let out = 0;
	for ( let i = 0; i < signal.length; i += 128 ) {

		out += analyser.push( signal.subarray( i, i + 128 ) ).length;
		const now = Math.min( signal.length, i + 128 ) / sampleRate;
		// Every hop at t <= now - latency is out; none beyond what has arrived.
		assert.ok( out >= Math.floor( ( now - analyser.latencyS ) * 100 ) + 1, `at ${ now } s only ${ out } hops` );
		assert.ok( out <= Math.floor( now * 100 ) + 1 );

	}

	assert.equal( out + analyser.flush().length, Math.floor( signal.length / sampleRate * 100 ) + 1 );
	assert.deepEqual( analyser.flush(), [] );
	assert.throws( () => analyser.push( signal ), /flushed/ );

} );

test( 'a bad sample rate or speaker group is refused, naming it', () => {

	assert.throws( () => createAnalyser( { sampleRate: 7999 } ), /sample rate must be a whole number of Hz, 8000 or more, got 7999/ );
	assert.throws( () => createAnalyser( { sampleRate: 44100.5 } ), RangeError );
	assert.throws( () => createAnalyser( {} ), RangeError );
	assert.throws( () => createAnalyser( { sampleRate: 16000, group: 'boy' } ), /unknown speaker group "boy" \(one of child, woman, man\)/ );
	assert.throws( () => createAnalyser( { sampleRate: 16000, group: 'toString' } ), /unknown speaker group/ );
	assert.equal( createAnalyser( { sampleRate: 16000 } ).group, 'woman' );

} );

test( 'the per-hop kernels allocate nothing', async () => {

	const sampleRate = 16000, narrowRate = 11000;
	const signal = utterance( sampleRate );
	const narrowSignal = utterance( narrowRate );
	const yin = createYin( { sampleRate: narrowRate, floor: 120, ceiling: 400 } );
	const formants = createFormantAnalysis( { sampleRate: narrowRate } );
	const moments = createMomentsAnalysis( { sampleRate, windowS: 0.02 } );
	const loudness = intensityWindow( sampleRate, 120 );
	const tracker = createPitchTracker( { candidates: yin.maxCandidates, lookahead: 5, floor: 120 } );
	const resampler = createResampler( sampleRate, narrowRate );
	const input = new SampleStream( resampler.halfTaps + 1, 2 * signal.length );
	const output = new SampleStream( 0, 2 * signal.length );
	input.append( signal );
	const hops = 2000; // enough that a few bytes per hop would fill the young generation
	const run = () => {

		for ( let k = 0; k < hops; k ++ ) {

			const n = 1 + ( k % 40 ) * 110;
			const count = yinCandidates( yin, narrowSignal, n );
			addPitchFrame( tracker, yin.candidateF0, yin.candidateAperiodicity, count, true );
			if ( tracker.frames > 5 ) decidePitch( tracker, tracker.frames - 6 );
			analyseFormants( formants, narrowSignal, n );
			analyseMoments( moments, signal, n );
			intensityDb( signal, n, loudness );

		}

		resampler.next = 0;
		output.end = 0;
		resampleStream( resampler, input, output );

	};
	run(); // let the JIT settle
	const quiet = await fewestGarbageCollections( run );
	const noisy = await garbageCollections( () => {

		for ( let k = 0; k < 200; k ++ ) analyseSamples( signal.subarray( 0, 200 ), sampleRate );

	} );
	assert.equal( quiet, 0, `${ quiet } collections during ${ hops } hops of every kernel` );
	assert.ok( noisy > 0, 'allocating should trigger collections' );

} );
