// `npm run measure` (scripts/measure.mjs): one JSON line per hop with the documented keys,
// rounded; `file` first with several files; status 2 and one line on stderr for what it cannot
// read or understand.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { spawnSync } from 'node:child_process';
import { mkdtempSync, rmSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { dirname, join, resolve } from 'node:path';
import { fileURLToPath } from 'node:url';
import { vowel, writeWav } from './support/listenSignals.js';

const SCRIPT = resolve( dirname( fileURLToPath( import.meta.url ) ), '..', '..', 'scripts', 'measure.mjs' );
const KEYS = [ 't', 'f0', 'voiced', 'intensity_db', 'formants', 'bandwidths', 'centroid', 'spread', 'skew', 'peak', 'f3_minus_f2' ];

const measure = ( ...args ) => spawnSync( process.execPath, [ SCRIPT, ...args ], { encoding: 'utf8' } );

/** A directory with a 0.3 s vowel at 16 kHz (F0 200 Hz), the same at 44.1 kHz in stereo, and a text file. */
function fixtures() {

	const dir = mkdtempSync( join( tmpdir(), 'glasshead-measure-' ) );
	const one = vowel( { sampleRate: 16000, seconds: 0.3, f0: 200, formants: [ 700, 1200, 2600, 3500, 4500 ], bandwidths: [ 80, 100, 150, 200, 250 ] } );
	writeFileSync( join( dir, 'a.wav' ), writeWav( { sampleRate: 16000, channels: 1, bits: 16, frames: Array.from( one, ( v ) => [ v ] ) } ) );
	const two = vowel( { sampleRate: 44100, seconds: 0.25, f0: 200, formants: [ 700, 1200, 2600, 3500, 4500 ], bandwidths: [ 80, 100, 150, 200, 250 ] } );
	writeFileSync( join( dir, 'b.wav' ), writeWav( { sampleRate: 44100, channels: 2, bits: 24, frames: Array.from( two, ( v ) => [ v, v ] ) } ) );
	writeFileSync( join( dir, 'notes.wav' ), 'not audio\n' );
	return dir;

}

test( 'one file: a JSON object per hop with exactly the documented keys, rounded', () => {

	const dir = fixtures();
	try {

		const result = measure( join( dir, 'a.wav' ) );
		assert.equal( result.status, 0, result.stderr );
		const hops = result.stdout.trim().split( '\n' ).map( ( line ) => JSON.parse( line ) );
		assert.equal( hops.length, 31 );
		for ( const [ k, hop ] of hops.entries() ) {

			assert.deepEqual( Object.keys( hop ), KEYS );
			assert.equal( hop.t, k / 100 );
			for ( const hz of [ hop.f0, ...hop.formants, hop.centroid ] ) if ( hz !== null ) assert.equal( hz, Math.round( hz * 10 ) / 10 );

		}

		const middle = hops[ 15 ];
		assert.ok( middle.voiced && Math.abs( middle.f0 - 200 ) <= 1, `f0 ${ middle.f0 }` );
		assert.ok( Math.abs( middle.formants[ 0 ] - 700 ) <= 35, `F1 ${ middle.formants[ 0 ] }` );

	} finally {

		rmSync( dir, { recursive: true } );

	}

} );

test( 'several files in one run: each line names its file, and --group applies to all', () => {

	const dir = fixtures();
	try {

		const a = join( dir, 'a.wav' ), b = join( dir, 'b.wav' );
		const result = measure( a, '--group', 'child', b );
		assert.equal( result.status, 0, result.stderr );
		const hops = result.stdout.trim().split( '\n' ).map( ( line ) => JSON.parse( line ) );
		assert.deepEqual( Object.keys( hops[ 0 ] ), [ 'file', ...KEYS ] );
		assert.equal( hops.filter( ( h ) => h.file === a ).length, 31 );
		assert.equal( hops.filter( ( h ) => h.file === b ).length, 26 );
		const single = measure( a, '--group=child' ).stdout.trim().split( '\n' ).map( ( line ) => JSON.parse( line ) );
		const withoutFile = ( hop ) => Object.fromEntries( Object.entries( hop ).filter( ( [ key ] ) => key !== 'file' ) );
		assert.deepEqual( hops.filter( ( h ) => h.file === a ).map( withoutFile ), single );

	} finally {

		rmSync( dir, { recursive: true } );

	}

} );

test( 'a missing file, a file that is not a WAV or a bad --group: one line on stderr, status 2, nothing on stdout', () => {

	const dir = fixtures();
	try {

		const cases = [
			[ [ join( dir, 'a.wav' ), join( dir, 'missing.wav' ) ], /missing\.wav: no such file/ ],
			[ [ join( dir, 'notes.wav' ) ], /notes\.wav: not a WAV file/ ],
			[ [ join( dir, 'a.wav' ), '--group', 'boy' ], /--group must be one of child, woman, man, not "boy"/ ],
			[ [ join( dir, 'a.wav' ), '--group' ], /--group must be one of/ ],
			[ [ '--frobnicate', join( dir, 'a.wav' ) ], /unknown option --frobnicate/ ],
			[ [], /no WAV file given/ ],
		];
		for ( const [ args, message ] of cases ) {

			const result = measure( ...args );
			assert.equal( result.status, 2, `${ args.join( ' ' ) }: status ${ result.status }` );
			assert.equal( result.stdout, '' );
			assert.match( result.stderr, message );
			assert.equal( result.stderr.trim().split( '\n' ).length, 1, result.stderr );

		}

	} finally {

		rmSync( dir, { recursive: true } );

	}

} );

test( '--help says how to call it and that the default group is woman', () => {

	const result = measure( '--help' );
	assert.equal( result.status, 0 );
	assert.match( result.stdout, /npm run measure -- FILE\.wav/ );
	assert.match( result.stdout, /default woman/ );

} );
