// A minimal PNG decoder for screenshots (8-bit RGB or RGBA, not interlaced), so the tests can
// compare pixels without extra dependencies. PNG specification (W3C, 2003), sections 9 (filters)
// and 11 (chunks).

import { inflateSync } from 'node:zlib';

const SIGNATURE = Buffer.from( [ 137, 80, 78, 71, 13, 10, 26, 10 ] );

/** Decode a PNG buffer into { width, height, data: Uint8Array RGBA (4 * width * height) }. */
export function decodePng( buffer ) {

	if ( ! SIGNATURE.equals( buffer.subarray( 0, 8 ) ) ) throw new Error( 'not a PNG file' );
	let offset = 8, header = null;
	const idat = [];
	while ( offset < buffer.length ) {

		const length = buffer.readUInt32BE( offset );
		const type = buffer.toString( 'latin1', offset + 4, offset + 8 );
		const body = buffer.subarray( offset + 8, offset + 8 + length );
		if ( type === 'IHDR' ) {

			header = {
				width: body.readUInt32BE( 0 ), height: body.readUInt32BE( 4 ),
				depth: body[ 8 ], colorType: body[ 9 ], interlace: body[ 12 ],
			};

		} else if ( type === 'IDAT' ) idat.push( body );
		else if ( type === 'IEND' ) break;
		offset += 12 + length;

	}

	if ( ! header ) throw new Error( 'PNG has no IHDR chunk' );
	const { width, height, depth, colorType, interlace } = header;
	if ( depth !== 8 || ( colorType !== 2 && colorType !== 6 ) || interlace !== 0 ) {

		throw new Error( `unsupported PNG (depth ${ depth }, colour type ${ colorType }, interlace ${ interlace })` );

	}

	const channels = colorType === 6 ? 4 : 3;
	const stride = width * channels;
	const raw = inflateSync( Buffer.concat( idat ) );
	const pixels = new Uint8Array( height * stride );
	for ( let y = 0; y < height; y ++ ) {

		const filter = raw[ y * ( stride + 1 ) ];
		const line = raw.subarray( y * ( stride + 1 ) + 1, ( y + 1 ) * ( stride + 1 ) );
		const row = y * stride;
		for ( let x = 0; x < stride; x ++ ) {

			const a = x >= channels ? pixels[ row + x - channels ] : 0;
			const b = y > 0 ? pixels[ row - stride + x ] : 0;
			const c = x >= channels && y > 0 ? pixels[ row - stride + x - channels ] : 0;
			pixels[ row + x ] = ( line[ x ] + predictor( filter, a, b, c ) ) & 255;

		}

	}

	const data = new Uint8Array( 4 * width * height );
	for ( let i = 0; i < width * height; i ++ ) {

		for ( let k = 0; k < 3; k ++ ) data[ 4 * i + k ] = pixels[ channels * i + k ];
		data[ 4 * i + 3 ] = channels === 4 ? pixels[ channels * i + 3 ] : 255;

	}

	return { width, height, data };

}

function predictor( filter, a, b, c ) {

	switch ( filter ) {

		case 0: return 0;
		case 1: return a;
		case 2: return b;
		case 3: return ( a + b ) >> 1;
		case 4: {

			const p = a + b - c, pa = Math.abs( p - a ), pb = Math.abs( p - b ), pc = Math.abs( p - c );
			return pa <= pb && pa <= pc ? a : pb <= pc ? b : c;

		}

		default: throw new Error( `bad PNG filter type ${ filter }` );

	}

}

/**
 * Compare two decoded images of the same size: the mean absolute difference per channel (0..255)
 * and the fraction of pixels whose largest channel difference exceeds `threshold`.
 */
export function compareImages( a, b, threshold = 24 ) {

	if ( a.width !== b.width || a.height !== b.height ) throw new Error( `image sizes differ: ${ a.width }x${ a.height } vs ${ b.width }x${ b.height }` );
	let sum = 0, changed = 0;
	const n = a.width * a.height;
	for ( let i = 0; i < n; i ++ ) {

		let largest = 0;
		for ( let k = 0; k < 3; k ++ ) {

			const d = Math.abs( a.data[ 4 * i + k ] - b.data[ 4 * i + k ] );
			sum += d;
			largest = Math.max( largest, d );

		}

		if ( largest > threshold ) changed ++;

	}

	return { meanDifference: sum / ( 3 * n ), changedFraction: changed / n };

}

/** Euclidean distance between two [r, g, b] colours. */
export function colourDistance( a, b ) {

	return Math.hypot( a[ 0 ] - b[ 0 ], a[ 1 ] - b[ 1 ], a[ 2 ] - b[ 2 ] );

}

/** The [r, g, b] colour of a playwright page at CSS pixel (x, y) (deviceScaleFactor 1). */
export async function pagePixel( page, x, y ) {

	const image = decodePng( await page.screenshot( { clip: { x: Math.round( x ), y: Math.round( y ), width: 1, height: 1 } } ) );
	return [ image.data[ 0 ], image.data[ 1 ], image.data[ 2 ] ];

}
