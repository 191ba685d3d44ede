// The listening kernels on real recordings: Hillenbrand, Getty, Clark & Wheeler (1995), American
// English vowels in /hVd/ words by men, women and 10-12 year old children (JASA 97(5),
// 3099-3111), read from ../shared/data/speech/hillenbrand1995-dev (GLASSHEAD_DATA_DIR overrides
// ../shared/data), never copied here. The authors' F0 and formants at the vowel's steady state
// (tokens.csv: their hand-corrected LPC tracks; the steady-state time is the mean of their two
// judges') against ours at the hop nearest that time, through the WAV reader and the whole-file
// analyser, as `npm run measure` runs them.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { existsSync, readFileSync } from 'node:fs';
import { dirname, join, resolve } from 'node:path';
import { fileURLToPath } from 'node:url';
import { analyseSamples } from '../../web/src/core/listen/analyse.js';
import { parseWav } from '../../web/src/core/listen/wav.js';

const HERE = dirname( fileURLToPath( import.meta.url ) );
const DATA_DIR = process.env.GLASSHEAD_DATA_DIR ?? resolve( HERE, '..', '..', '..', 'shared', 'data' );
const HILLENBRAND = join( DATA_DIR, 'speech', 'hillenbrand1995-dev' );
const GROUP = { man: 'man', woman: 'woman', boy: 'child', girl: 'child' };

/** tokens.csv as objects (empty cells: not measurable), or a loud failure naming where it looked. */
function readTokens() {

	const path = join( HILLENBRAND, 'tokens.csv' );
	assert.ok( existsSync( path ), `Hillenbrand et al. (1995) recordings missing: no ${ path }; put the shared data at ../shared/data or set GLASSHEAD_DATA_DIR` );
	const [ header, ...lines ] = readFileSync( path, 'utf8' ).trim().split( /\r?\n/ );
	const names = header.split( ',' );
	return lines.map( ( line ) => Object.fromEntries( line.split( ',' ).map( ( value, k ) => [ names[ k ], value === '' ? null : value ] ) ) );

}

/** Our hop at the token's steady-state time. */
function measureToken( token ) {

	const path = join( HILLENBRAND, 'audio', `${ token.file }.wav` );
	assert.ok( existsSync( path ), `recording missing: ${ path }` );
	const { samples, sampleRate } = parseWav( readFileSync( path ) );
	const hops = analyseSamples( samples, sampleRate, { group: GROUP[ token.group ] } );
	const steadyS = ( Number( token.steady_ms_judge1 ) + Number( token.steady_ms_judge2 ) ) / 2000;
	return hops[ Math.round( steadyS * 100 ) ];

}

const relativeError = ( ours, theirs ) => ( ours === null ? Infinity : Math.abs( ours / theirs - 1 ) );

/**
 * A man, a woman, a boy and a girl, three vowels each (/æ/ had, /i/ heed, /u/ who'd), the first
 * talker of each group. F0 within 3 %, F1 and F2 within 10 %. One exception, kept visible:
 * m01ae's published F0 (174 Hz) is 4.3 % above what we measure at its steady state (166.4 Hz);
 * Praat's "To Pitch (ac)" (60-250 Hz) reads 166.4 Hz there too, so it is checked within 5 %.
 */
const HANDFUL = [ 'm01ae', 'm01iy', 'm01uw', 'w01ae', 'w01iy', 'w01uw', 'b01ae', 'b01iy', 'b01uw', 'g01ae', 'g01iy', 'g01uw' ];
const F0_TOLERANCE = { m01ae: 0.05 };

test( 'a handful of real vowels: F0 within 3 %, F1 and F2 within 10 % of the authors\' at the steady state', () => {

	const tokens = readTokens();
	const failures = [];
	for ( const file of HANDFUL ) {

		const token = tokens.find( ( t ) => t.file === file );
		assert.ok( token, `${ file } not in tokens.csv` );
		const hop = measureToken( token );
		const checks = [
			[ 'F0', hop.f0, Number( token.f0_ss ), F0_TOLERANCE[ file ] ?? 0.03 ],
			[ 'F1', hop.formants[ 0 ], Number( token.F1_ss ), 0.1 ],
			[ 'F2', hop.formants[ 1 ], Number( token.F2_ss ), 0.1 ],
		];
		for ( const [ name, ours, theirs, tolerance ] of checks ) {

			if ( ! ( relativeError( ours, theirs ) <= tolerance ) ) failures.push( `${ file } ${ name }: ours ${ ours }, theirs ${ theirs } (tolerance ${ tolerance * 100 } %)` );

		}

	}

	assert.deepEqual( failures, [] );

} );

test( 'all 576 vowels: median F0 error at most 1.5 %, octave errors and unvoiced steady states each in at most 1 % of tokens', () => {

	const tokens = readTokens();
	assert.equal( tokens.length, 576 );
	const f0Errors = [], f1Errors = [], f2Errors = [];
	const octave = [], unvoiced = [];
	for ( const token of tokens ) {

		const hop = measureToken( token );
		const theirs = Number( token.f0_ss );
		if ( hop.f0 === null ) unvoiced.push( token.file );
		// An octave error: nearer to double or half the authors' F0 than to it.
		else if ( Math.abs( Math.log2( hop.f0 / theirs ) ) > 0.5 ) octave.push( `${ token.file } (${ hop.f0.toFixed( 1 ) } against ${ theirs })` );
		f0Errors.push( relativeError( hop.f0, theirs ) );
		if ( token.F1_ss !== null ) f1Errors.push( relativeError( hop.formants[ 0 ], Number( token.F1_ss ) ) );
		if ( token.F2_ss !== null ) f2Errors.push( relativeError( hop.formants[ 1 ], Number( token.F2_ss ) ) );

	}

	const median = ( values ) => values.slice().sort( ( a, b ) => a - b )[ values.length >> 1 ];
	const within10 = ( values ) => values.filter( ( e ) => e <= 0.1 ).length / values.length;
	assert.ok( median( f0Errors ) <= 0.015, `median F0 error ${ ( 100 * median( f0Errors ) ).toFixed( 2 ) } %` );
	assert.ok( octave.length <= 0.01 * tokens.length, `octave errors: ${ octave.join( ', ' ) }` );
	assert.ok( unvoiced.length <= 0.01 * tokens.length, `unvoiced at the steady state: ${ unvoiced.join( ', ' ) }` );
	// Formants (Praat's method, not hand-corrected): most within 10 %, the median within 3 %.
	for ( const [ name, errors ] of [ [ 'F1', f1Errors ], [ 'F2', f2Errors ] ] ) {

		assert.ok( median( errors ) <= 0.03, `median ${ name } error ${ ( 100 * median( errors ) ).toFixed( 2 ) } %` );
		assert.ok( within10( errors ) >= 0.9, `${ name } within 10 % in ${ ( 100 * within10( errors ) ).toFixed( 1 ) } % of tokens` );

	}

} );
