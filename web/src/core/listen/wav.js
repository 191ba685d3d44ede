// Reading a RIFF WAVE file into mono samples: integer PCM of 8, 16, 24 or 32 bits, IEEE float of
// 32 or 64 bits, in the plain format chunk or WAVE_FORMAT_EXTENSIBLE, any number of channels
// (averaged to one) and any sample rate. Anything else is refused with a WavError that says what
// the file is and what is missing.
//
// Layout: Microsoft's "Multimedia Programming Interface and Data Specifications 1.0" (1991), the
// RIFF chunks and the `fmt ` chunk, and "Multiple channel audio data and WAVE files" (the
// extensible format: cbSize 22, valid bits, channel mask, then a 16-byte sub-format GUID whose
// first two bytes are the format code). Little-endian throughout; chunks are padded to even sizes.

/** The format codes read: integer PCM and IEEE float; extensible ones name one in their GUID. */
export const WAVE_FORMAT_PCM = 1;
export const WAVE_FORMAT_IEEE_FLOAT = 3;
export const WAVE_FORMAT_EXTENSIBLE = 0xFFFE;

/** Names for the codes most often met, so that an error can say what the file holds. */
const FORMAT_NAMES = { 2: 'Microsoft ADPCM', 6: 'A-law', 7: 'mu-law', 17: 'IMA ADPCM', 85: 'MPEG layer 3' };

/** A file that is not a WAV, or a WAV this reader does not decode. */
export class WavError extends Error {

	constructor( message ) {

		super( message );
		this.name = 'WavError';

	}

}

const tag = ( view, at ) => String.fromCharCode( view.getUint8( at ), view.getUint8( at + 1 ), view.getUint8( at + 2 ), view.getUint8( at + 3 ) );

/**
 * Decode a WAV file.
 * @param {ArrayBuffer | ArrayBufferView} data the whole file (a Node Buffer works too)
 * @returns {{ sampleRate: number, channels: number, bitsPerSample: number, format: 'pcm' | 'float',
 *   samples: Float32Array }} samples: the channels' mean, integers scaled to [-1, 1)
 */
export function parseWav( data ) {

	const view = ArrayBuffer.isView( data ) ? new DataView( data.buffer, data.byteOffset, data.byteLength )
		: data instanceof ArrayBuffer ? new DataView( data ) : null;
	if ( ! view ) throw new WavError( 'not a WAV file: expected the bytes of a file (ArrayBuffer or typed array)' );
	if ( view.byteLength < 12 ) throw new WavError( `not a WAV file: ${ view.byteLength } bytes, too short for a RIFF header` );
	const riff = tag( view, 0 );
	if ( riff === 'RIFX' || riff === 'RF64' ) throw new WavError( `a ${ riff } file (${ riff === 'RIFX' ? 'big-endian' : '64-bit' } WAV) is not read; save it as a plain RIFF WAV` );
	if ( riff !== 'RIFF' || tag( view, 8 ) !== 'WAVE' ) throw new WavError( 'not a WAV file: no RIFF/WAVE header' );

	let format = null;
	let dataStart = - 1, dataBytes = 0;
	for ( let at = 12; at + 8 <= view.byteLength; ) {

		const id = tag( view, at );
		const size = view.getUint32( at + 4, true );
		const body = at + 8;
		if ( id === 'fmt ' ) format = readFormat( view, body, size );
		else if ( id === 'data' && dataStart < 0 ) {

			dataStart = body;
			// A file written as a stream may say 0 or 0xFFFFFFFF: take what is there.
			dataBytes = Math.min( size, view.byteLength - body );
			if ( size === 0 || size === 0xFFFFFFFF ) dataBytes = view.byteLength - body;

		}

		at = body + size + ( size & 1 );

	}

	if ( ! format ) throw new WavError( 'WAV file without a format ("fmt ") chunk' );
	if ( dataStart < 0 ) throw new WavError( 'WAV file without a "data" chunk' );
	const { code, channels, sampleRate, blockAlign, bitsPerSample } = format;
	if ( code !== WAVE_FORMAT_PCM && code !== WAVE_FORMAT_IEEE_FLOAT ) {

		const name = FORMAT_NAMES[ code ] ? ` (${ FORMAT_NAMES[ code ] })` : '';
		throw new WavError( `WAV format ${ code }${ name } is not PCM: only integer PCM and IEEE float samples are read` );

	}

	if ( channels < 1 ) throw new WavError( 'WAV file with no channels' );
	if ( ! ( sampleRate > 0 ) ) throw new WavError( `WAV file with a sample rate of ${ sampleRate } Hz` );
	const isFloat = code === WAVE_FORMAT_IEEE_FLOAT;
	const bytes = bitsPerSample / 8;
	const readable = isFloat ? bitsPerSample === 32 || bitsPerSample === 64 : [ 8, 16, 24, 32 ].includes( bitsPerSample );
	if ( ! readable ) throw new WavError( `WAV ${ isFloat ? 'float' : 'PCM' } samples of ${ bitsPerSample } bits are not read (PCM 8, 16, 24, 32; float 32, 64)` );
	if ( blockAlign < channels * bytes ) throw new WavError( `WAV block of ${ blockAlign } bytes cannot hold ${ channels } samples of ${ bitsPerSample } bits` );

	const frames = Math.floor( dataBytes / blockAlign );
	const samples = new Float32Array( frames );
	const read = sampleReader( view, isFloat, bitsPerSample );
	const mix = 1 / channels;
	for ( let i = 0; i < frames; i ++ ) {

		let sum = 0;
		const at = dataStart + i * blockAlign;
		for ( let c = 0; c < channels; c ++ ) sum += read( at + c * bytes );
		samples[ i ] = sum * mix;

	}

	return { sampleRate, channels, bitsPerSample, format: isFloat ? 'float' : 'pcm', samples };

}

/** The `fmt ` chunk: the format code (resolved through an extensible chunk's GUID) and layout. */
function readFormat( view, at, size ) {

	if ( size < 16 || at + 16 > view.byteLength ) throw new WavError( `WAV format chunk of ${ size } bytes, too short (16 at least)` );
	let code = view.getUint16( at, true );
	if ( code === WAVE_FORMAT_EXTENSIBLE ) {

		if ( size < 40 || at + 40 > view.byteLength ) throw new WavError( 'WAVE_FORMAT_EXTENSIBLE format chunk too short for its sub-format' );
		code = view.getUint16( at + 24, true );

	}

	return {
		code,
		channels: view.getUint16( at + 2, true ),
		sampleRate: view.getUint32( at + 4, true ),
		blockAlign: view.getUint16( at + 12, true ),
		bitsPerSample: view.getUint16( at + 14, true ),
	};

}

/** A reader of one sample at a byte offset, as a number in [-1, 1) for integers. */
function sampleReader( view, isFloat, bits ) {

	if ( isFloat ) return bits === 32 ? ( at ) => view.getFloat32( at, true ) : ( at ) => view.getFloat64( at, true );
	switch ( bits ) {

		case 8: return ( at ) => ( view.getUint8( at ) - 128 ) / 128; // 8-bit WAV is unsigned
		case 16: return ( at ) => view.getInt16( at, true ) / 32768;
		case 24: return ( at ) => ( ( view.getUint8( at + 2 ) << 24 >> 8 ) | ( view.getUint8( at + 1 ) << 8 ) | view.getUint8( at ) ) / 8388608;
		default: return ( at ) => view.getInt32( at, true ) / 2147483648;

	}

}
