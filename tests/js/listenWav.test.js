// The WAV reader (web/src/core/listen/wav.js) on files written here byte by byte: every sample
// format it reads, channels mixed to mono, the chunk walk, and a clear refusal of everything else.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { WavError, parseWav } from '../../web/src/core/listen/wav.js';
import { writeWav } from './support/listenSignals.js';
import { nearArray } from './support/near.js';

/** A few values that exercise sign, zero and both ends of the range. */
const VALUES = [ 0, 0.5, - 0.5, 0.25, - 1, 0.999, - 0.001 ];
const mono = VALUES.map( ( v ) => [ v ] );

/** One quantisation step of an integer format, or float32's resolution near 1 if coarser. */
const step = ( bits ) => Math.max( 2 / 2 ** bits, 2 ** - 23 );

for ( const bits of [ 8, 16, 24, 32 ] ) {

	test( `${ bits }-bit integer PCM reads back within one quantisation step`, () => {

		const wav = parseWav( writeWav( { sampleRate: 16000, channels: 1, bits, frames: mono } ) );
		assert.equal( wav.sampleRate, 16000 );
		assert.equal( wav.bitsPerSample, bits );
		assert.equal( wav.format, 'pcm' );
		assert.ok( wav.samples instanceof Float32Array );
		nearArray( Array.from( wav.samples ), VALUES, step( bits ), `${ bits }-bit samples` );

	} );

}

test( '24-bit negative samples keep their sign (the top byte is sign-extended)', () => {

	const wav = parseWav( writeWav( { sampleRate: 44100, channels: 1, bits: 24, frames: [ [ - 1 / 8388608 ], [ - 0.75 ], [ 0.75 ] ] } ) );
	assert.deepEqual( Array.from( wav.samples ), [ - 1 / 8388608, - 0.75, 0.75 ] );

} );

test( '32- and 64-bit float samples read back exactly (as float32)', () => {

	for ( const bits of [ 32, 64 ] ) {

		const wav = parseWav( writeWav( { sampleRate: 48000, channels: 1, bits, float: true, frames: mono } ) );
		assert.equal( wav.format, 'float' );
		assert.deepEqual( Array.from( wav.samples ), VALUES.map( Math.fround ) );

	}

} );

test( 'stereo is mixed to mono by the mean of the channels', () => {

	const frames = [ [ 0.5, - 0.5 ], [ 0.25, 0.75 ], [ - 1, - 0.5 ] ];
	const wav = parseWav( writeWav( { sampleRate: 22050, channels: 2, bits: 16, frames } ) );
	assert.equal( wav.channels, 2 );
	assert.equal( wav.samples.length, 3 );
	nearArray( Array.from( wav.samples ), [ 0, 0.5, - 0.75 ], 1e-4, 'mixed samples' );

} );

test( 'WAVE_FORMAT_EXTENSIBLE files read by their sub-format (PCM and float)', () => {

	const pcm = parseWav( writeWav( { sampleRate: 96000, channels: 1, bits: 24, extensible: true, frames: mono } ) );
	assert.equal( pcm.format, 'pcm' );
	assert.equal( pcm.sampleRate, 96000 );
	nearArray( Array.from( pcm.samples ), VALUES, step( 24 ), 'extensible 24-bit' );
	const float = parseWav( writeWav( { sampleRate: 8000, channels: 2, bits: 32, float: true, extensible: true, frames: [ [ 0.5, 0.25 ] ] } ) );
	assert.equal( float.format, 'float' );
	assert.deepEqual( Array.from( float.samples ), [ 0.375 ] );

} );

test( 'chunks before the data are skipped, odd sizes with their pad byte', () => {

	const plain = writeWav( { sampleRate: 16000, channels: 1, bits: 16, frames: mono } );
	// Insert a 3-byte LIST chunk (padded to 4) after the format chunk.
	const fmtEnd = 12 + 8 + 16;
	const extra = new Uint8Array( [ 0x4C, 0x49, 0x53, 0x54, 3, 0, 0, 0, 1, 2, 3, 0 ] );
	const file = new Uint8Array( plain.length + extra.length );
	file.set( plain.subarray( 0, fmtEnd ) );
	file.set( extra, fmtEnd );
	file.set( plain.subarray( fmtEnd ), fmtEnd + extra.length );
	nearArray( Array.from( parseWav( file ).samples ), VALUES, step( 16 ), 'samples after a LIST chunk' );

} );

test( 'a data chunk whose size says 0xFFFFFFFF (written as a stream) is read to the end of the file', () => {

	const file = writeWav( { sampleRate: 16000, channels: 1, bits: 16, frames: mono } );
	new DataView( file.buffer ).setUint32( 12 + 8 + 16 + 4, 0xFFFFFFFF, true );
	assert.equal( parseWav( file ).samples.length, VALUES.length );

} );

test( 'a view into a larger buffer (as Node Buffers are) reads only its own bytes', () => {

	const file = writeWav( { sampleRate: 16000, channels: 1, bits: 16, frames: mono } );
	const big = new Uint8Array( file.length + 100 ).fill( 0x55 );
	big.set( file, 37 );
	const wav = parseWav( big.subarray( 37, 37 + file.length ) );
	assert.equal( wav.samples.length, VALUES.length );
	assert.equal( parseWav( big.buffer.slice( 37, 37 + file.length ) ).samples.length, VALUES.length );

} );

/** parseWav must throw a WavError whose message matches. */
function refuses( bytes, pattern ) {

	assert.throws( () => parseWav( bytes ), ( error ) => error instanceof WavError && pattern.test( error.message ), `expected a WavError matching ${ pattern }` );

}

test( 'what is not a WAV is refused, saying so', () => {

	refuses( new TextEncoder().encode( 'name,value\nf0,120\n' ), /not a WAV file: no RIFF\/WAVE header/ );
	refuses( new Uint8Array( 4 ), /too short/ );
	refuses( 'RIFF', /expected the bytes of a file/ );
	const riffAvi = writeWav( { sampleRate: 16000, channels: 1, bits: 16, frames: mono } );
	riffAvi.set( [ 0x41, 0x56, 0x49, 0x20 ], 8 ); // RIFF AVI
	refuses( riffAvi, /no RIFF\/WAVE header/ );
	const rifx = writeWav( { sampleRate: 16000, channels: 1, bits: 16, frames: mono } );
	rifx.set( [ 0x52, 0x49, 0x46, 0x58 ], 0 );
	refuses( rifx, /RIFX.*big-endian/ );

} );

test( 'WAVs that are not PCM or float, or lack a chunk, are refused naming what is wrong', () => {

	const alaw = writeWav( { sampleRate: 8000, channels: 1, bits: 8, frames: mono } );
	new DataView( alaw.buffer ).setUint16( 20, 6, true );
	refuses( alaw, /format 6 \(A-law\) is not PCM/ );
	const adpcmExtensible = writeWav( { sampleRate: 8000, channels: 1, bits: 16, extensible: true, frames: mono } );
	new DataView( adpcmExtensible.buffer ).setUint16( 44, 2, true );
	refuses( adpcmExtensible, /format 2 \(Microsoft ADPCM\) is not PCM/ );
	const twelveBits = writeWav( { sampleRate: 8000, channels: 1, bits: 16, frames: mono } );
	new DataView( twelveBits.buffer ).setUint16( 34, 12, true );
	refuses( twelveBits, /samples of 12 bits are not read/ );
	const float16 = writeWav( { sampleRate: 8000, channels: 1, bits: 16, frames: mono } );
	new DataView( float16.buffer ).setUint16( 20, 3, true );
	refuses( float16, /float samples of 16 bits/ );

	const noData = writeWav( { sampleRate: 8000, channels: 1, bits: 16, frames: mono } );
	noData.set( [ 0x64, 0x61, 0x74, 0x78 ], 12 + 8 + 16 ); // "datx"
	refuses( noData, /without a "data" chunk/ );
	const noFormat = writeWav( { sampleRate: 8000, channels: 1, bits: 16, frames: mono } );
	noFormat.set( [ 0x66, 0x6D, 0x74, 0x78 ], 12 ); // "fmtx"
	refuses( noFormat, /without a format/ );

} );
