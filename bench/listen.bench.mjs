// Benchmark: the listening analysis per 10 ms hop (web/src/core/listen/), on real recordings of a
// man, a woman and a boy (Hillenbrand et al. 1995, 16 kHz) and on the same recordings resampled
// to 48 kHz, a browser microphone's rate. Prints the medians of:
//   live      the streaming analyser fed AudioWorklet quanta of 128 samples: resampling, pitch
//             candidates and tracking, intensity, formants, spectral moments (goal: 0.3 ms per hop)
//   kernels   the per-hop kernels on the same frames: YIN's difference by FFT, moments by FFT
//   baseline  the same per-hop kernels with the spectra done the naive way, in the same run:
//             YIN's difference function summed directly (O(W maxLag)) and the moments' power
//             spectrum by a DFT over precomputed twiddles (O(N^2)), no trigonometry per hop
// and their ratio. Checks: the baseline's candidates and moments are the kernels' (1e-9), and the
// live analyser's hops are the kernels' on the same frames (same samples, same numbers).
//
//   node bench/listen.bench.mjs            (GLASSHEAD_DATA_DIR overrides ../shared/data)
//   GLASSHEAD_BENCH_QUICK=1                 3 runs instead of 21
import { readFileSync } from 'node:fs';
import { dirname, join, resolve } from 'node:path';
import { fileURLToPath } from 'node:url';
import { performance } from 'node:perf_hooks';

import { createAnalyser } from '../web/src/core/listen/analyse.js';
import { SampleStream, centreSample, windowStart } from '../web/src/core/listen/frames.js';
import { intensityDb, intensityWindow } from '../web/src/core/listen/intensity.js';
import { analyseFormants, createFormantAnalysis } from '../web/src/core/listen/lpc.js';
import {
	MOMENT_CENTROID, MOMENT_SLOTS, analyseMoments, createMomentsAnalysis, spectralMoments,
} from '../web/src/core/listen/moments.js';
import { GROUPS, MOMENTS_WINDOW_S } from '../web/src/core/listen/params.js';
import { collectCandidates, createYin, yinCandidates } from '../web/src/core/listen/pitch.js';
import { createResampler, resampleStream } from '../web/src/core/listen/resample.js';
import { parseWav } from '../web/src/core/listen/wav.js';
import { check, count } from './support/quick.mjs';
import { median } from './support/stats.mjs';

const HERE = dirname( fileURLToPath( import.meta.url ) );
const DATA_DIR = process.env.GLASSHEAD_DATA_DIR ?? resolve( HERE, '..', '..', 'shared', 'data' );
const RUNS = count( 21, 3 );
const GOAL_MS = 0.3;
const RECORDINGS = [ [ 'm01ae', 'man' ], [ 'w01ae', 'woman' ], [ 'b01ae', 'child' ] ];

/** The whole of `signal` through a resampler (zeros after it, so that every sample is made). */
function resampleAll( signal, from, to, lead = 0 ) {

	const resampler = createResampler( from, to );
	const input = new SampleStream( resampler.halfTaps + 1, signal.length + 2 * resampler.halfTaps + 16 );
	const output = new SampleStream( lead, Math.ceil( signal.length * to / from ) + lead + 16 );
	input.append( signal );
	input.appendZeros( 2 * resampler.halfTaps );
	resampleStream( resampler, input, output );
	return output;

}

/** A stream holding `signal` after `lead` zeros, as the analyser holds its input. */
function padded( signal, lead ) {

	const stream = new SampleStream( lead, signal.length + 2 * lead + 16 );
	stream.append( signal );
	stream.appendZeros( lead );
	return stream;

}

/** YIN's d and d' (pitch.js's, the levels equalised) by their definition: for each lag, sums over the integration window. */
function naiveDifference( yin, samples, start ) {

	const { integration, lags, difference, normalised } = yin;
	let energy = 0;
	for ( let j = 0; j < yin.frameLength; j ++ ) energy += samples[ start + j ] * samples[ start + j ];
	if ( energy === 0 ) return false;
	difference[ 0 ] = 0;
	normalised[ 0 ] = 1;
	let running = 0, e0 = 0;
	for ( let j = 0; j < integration; j ++ ) e0 += samples[ start + j ] * samples[ start + j ];
	for ( let tau = 1; tau <= lags; tau ++ ) {

		let r = 0, et = 0;
		for ( let j = 0; j < integration; j ++ ) {

			const a = samples[ start + j ], b = samples[ start + j + tau ];
			r += a * b;
			et += b * b;

		}

		const d = Math.max( 0, ( e0 + et ) * ( 1 - ( e0 > 0 && et > 0 ? r / Math.sqrt( e0 * et ) : 0 ) ) );
		difference[ tau ] = d;
		running += d;
		normalised[ tau ] = running > 0 ? d * tau / running : 1;

	}

	return true;

}

/** Moments with the power spectrum by a DFT over precomputed twiddles (the analysis's own window). */
function createNaiveMoments( analysis ) {

	const size = analysis.fft.size, bins = analysis.fft.bins;
	const cos = new Float64Array( bins * size ), sin = new Float64Array( bins * size );
	for ( let k = 0; k < bins; k ++ ) for ( let j = 0; j < size; j ++ ) {

		cos[ k * size + j ] = Math.cos( 2 * Math.PI * k * j / size );
		sin[ k * size + j ] = Math.sin( 2 * Math.PI * k * j / size );

	}

	const frame = new Float64Array( analysis.frameLength ), power = new Float64Array( bins ), result = new Float64Array( MOMENT_SLOTS );
	return ( samples, start ) => {

		const n = analysis.frameLength;
		let mean = 0;
		for ( let i = 0; i < n; i ++ ) mean += samples[ start + i ];
		mean /= n;
		for ( let i = 0; i < n; i ++ ) frame[ i ] = ( samples[ start + i ] - mean ) * analysis.window[ i ];
		for ( let k = 0; k < bins; k ++ ) {

			let re = 0, im = 0;
			const row = k * size;
			for ( let j = 0; j < n; j ++ ) { // the zero padding adds nothing

				re += frame[ j ] * cos[ row + j ];
				im -= frame[ j ] * sin[ row + j ];

			}

			power[ k ] = re * re + im * im;

		}

		return spectralMoments( power, analysis.binHz, analysis.lo, analysis.hi, result );

	};

}

/** Everything one recording at one rate needs: streams, kernels, the hops' frame positions. */
function prepare( signal, sampleRate, group ) {

	const settings = GROUPS[ group ];
	const narrowRate = 2 * settings.formantCeiling;
	const yin = createYin( { sampleRate: narrowRate, floor: settings.pitchFloor, ceiling: settings.pitchCeiling } );
	const formants = createFormantAnalysis( { sampleRate: narrowRate } );
	const loudness = intensityWindow( sampleRate, settings.pitchFloor );
	const moments = createMomentsAnalysis( { sampleRate, windowS: MOMENTS_WINDOW_S } );
	const lead = Math.max( loudness.length, moments.frameLength, yin.frameLength, formants.frameLength ) + 2;
	const input = padded( signal, lead );
	const narrow = resampleAll( signal, sampleRate, narrowRate, lead );
	const hops = Math.floor( signal.length / sampleRate * 100 ) + 1;
	const at = ( k ) => {

		const c = centreSample( k / 100, sampleRate ), n = centreSample( k / 100, narrowRate );
		return {
			loud: input.offset( windowStart( c, loudness.length ) ),
			moments: input.offset( windowStart( c, moments.frameLength ) ),
			pitch: narrow.offset( windowStart( n, yin.frameLength ) ),
			formants: narrow.offset( windowStart( n, formants.frameLength ) ),
		};

	};

	const positions = Array.from( { length: hops }, ( _, k ) => at( k ) );
	return { signal, sampleRate, group, yin, formants, loudness, moments, naiveMoments: createNaiveMoments( moments ), input, narrow, positions };

}

let sink = 0;

function kernelsPass( p ) {

	for ( const at of p.positions ) {

		sink += intensityDb( p.input.data, at.loud, p.loudness ) ?? 0;
		sink += yinCandidates( p.yin, p.narrow.data, at.pitch );
		sink += analyseFormants( p.formants, p.narrow.data, at.formants );
		sink += analyseMoments( p.moments, p.input.data, at.moments )[ MOMENT_CENTROID ] || 0;

	}

}

function baselinePass( p ) {

	for ( const at of p.positions ) {

		sink += intensityDb( p.input.data, at.loud, p.loudness ) ?? 0;
		if ( naiveDifference( p.yin, p.narrow.data, at.pitch ) ) sink += collectCandidates( p.yin );
		sink += analyseFormants( p.formants, p.narrow.data, at.formants );
		sink += p.naiveMoments( p.input.data, at.moments )[ MOMENT_CENTROID ] || 0;

	}

}

/** The analyser is made before the clock starts: the app makes it once, when listening starts. */
function livePass( p, analyser ) {

	let hops = 0;
	for ( let i = 0; i < p.signal.length; i += 128 ) hops += analyser.push( p.signal.subarray( i, i + 128 ) ).length;
	hops += analyser.flush().length;
	return hops;

}

/** The first disagreement between the kernels and the baseline (or the live analyser), or ''. */
function differences( p ) {

	const close = ( a, b ) => Math.abs( a - b ) <= 1e-9 * Math.max( 1, Math.abs( a ), Math.abs( b ) ) || ( Number.isNaN( a ) && Number.isNaN( b ) );
	const live = createAnalyser( { sampleRate: p.sampleRate, group: p.group } );
	const hops = [ ...live.push( p.signal ), ...live.flush() ];
	if ( hops.length !== p.positions.length ) return `live gave ${ hops.length } hops, expected ${ p.positions.length }`;
	for ( const [ k, at ] of p.positions.entries() ) {

		const where = `${ p.group } at ${ p.sampleRate } Hz, hop ${ k }`;
		const count = yinCandidates( p.yin, p.narrow.data, at.pitch );
		const f0s = Array.from( p.yin.candidateF0.subarray( 0, count ) ), aps = Array.from( p.yin.candidateAperiodicity.subarray( 0, count ) );
		const naiveCount = naiveDifference( p.yin, p.narrow.data, at.pitch ) ? collectCandidates( p.yin ) : 0;
		if ( naiveCount !== count ) return `${ where }: ${ naiveCount } naive candidates against ${ count }`;
		for ( let i = 0; i < count; i ++ ) {

			if ( ! close( p.yin.candidateF0[ i ], f0s[ i ] ) || Math.abs( p.yin.candidateAperiodicity[ i ] - aps[ i ] ) > 1e-9 ) return `${ where }: candidate ${ i } naive ${ p.yin.candidateF0[ i ] } against ${ f0s[ i ] }`;

		}

		const fast = analyseMoments( p.moments, p.input.data, at.moments ).slice();
		const slow = p.naiveMoments( p.input.data, at.moments );
		for ( let i = 0; i < MOMENT_SLOTS; i ++ ) if ( ! close( fast[ i ], slow[ i ] ) ) return `${ where }: moment ${ i } by FFT ${ fast[ i ] }, by DFT ${ slow[ i ] }`;

		const n = analyseFormants( p.formants, p.narrow.data, at.formants );
		const hop = hops[ k ];
		if ( ( n > 0 ? p.formants.frequencies[ 0 ] : null ) !== hop.formants[ 0 ] ) return `${ where }: live F1 ${ hop.formants[ 0 ] }, kernel ${ p.formants.frequencies[ 0 ] }`;
		if ( ( fast[ MOMENT_CENTROID ] || null ) !== hop.centroid ) return `${ where }: live centroid ${ hop.centroid }, kernel ${ fast[ MOMENT_CENTROID ] }`;
		if ( intensityDb( p.input.data, at.loud, p.loudness ) !== hop.intensity_db ) return `${ where }: live intensity ${ hop.intensity_db }`;

	}

	return '';

}

const cases = [];
for ( const [ file, group ] of RECORDINGS ) {

	const wav = parseWav( readFileSync( join( DATA_DIR, 'speech', 'hillenbrand1995-dev', 'audio', `${ file }.wav` ) ) );
	cases.push( prepare( wav.samples, wav.sampleRate, group ) );
	const up = resampleAll( wav.samples, wav.sampleRate, 48000 );
	cases.push( prepare( up.data.slice( 0, Math.round( wav.samples.length * 48000 / wav.sampleRate ) ), 48000, group ) );

}

console.log( `Listening analysis per 10 ms hop, median of ${ RUNS } runs` );
const results = [];
for ( const p of cases ) {

	const hops = p.positions.length;
	const times = { live: [], kernels: [], baseline: [] };
	const fresh = () => createAnalyser( { sampleRate: p.sampleRate, group: p.group } );
	livePass( p, fresh() );
	kernelsPass( p );
	baselinePass( p ); // warm-up
	for ( let run = 0; run < RUNS; run ++ ) {

		// Interleaved, so that the machine's load falls on all three alike.
		const analyser = fresh();
		let t0 = performance.now();
		livePass( p, analyser );
		times.live.push( ( performance.now() - t0 ) / hops );
		t0 = performance.now();
		kernelsPass( p );
		times.kernels.push( ( performance.now() - t0 ) / hops );
		t0 = performance.now();
		baselinePass( p );
		times.baseline.push( ( performance.now() - t0 ) / hops );

	}

	const row = {
		group: p.group, sample_rate: p.sampleRate, hops,
		live_median_ms_per_hop: Number( median( times.live ).toPrecision( 3 ) ),
		kernels_median_ms_per_hop: Number( median( times.kernels ).toPrecision( 3 ) ),
		baseline_median_ms_per_hop: Number( median( times.baseline ).toPrecision( 3 ) ),
	};
	row.speedup = Number( ( row.baseline_median_ms_per_hop / row.kernels_median_ms_per_hop ).toFixed( 1 ) );
	results.push( row );
	console.log( `  ${ p.group.padEnd( 5 ) } ${ String( p.sampleRate ).padStart( 5 ) } Hz, ${ hops } hops: live ${ ( row.live_median_ms_per_hop * 1000 ).toFixed( 1 ) } us, kernels ${ ( row.kernels_median_ms_per_hop * 1000 ).toFixed( 1 ) } us, baseline ${ ( row.baseline_median_ms_per_hop * 1000 ).toFixed( 1 ) } us per hop (${ row.speedup }x)` );

}

const worstLive = Math.max( ...results.map( ( r ) => r.live_median_ms_per_hop ) );
console.log( `  slowest live median ${ worstLive } ms per hop; goal <= ${ GOAL_MS } ms: ${ worstLive <= GOAL_MS ? 'met' : 'NOT met' } (${ sink > 0 ? 'checked' : '?' })` );
console.log( JSON.stringify( { benchmark: 'listen', runs: RUNS, goal_ms: GOAL_MS, goal_met: worstLive <= GOAL_MS, results } ) );
for ( const p of cases ) {

	const first = differences( p );
	check( `${ p.group } at ${ p.sampleRate } Hz: the naive spectra give the kernels' candidates and moments, and the live analyser the kernels' hops`, first === '', first );

}
