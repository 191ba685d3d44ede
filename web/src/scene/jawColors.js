// Per-vertex colours of the jaw meshes, so that each reads at a glance:
//   maxilla:  ivory teeth, pink gums, pink palate (the roof of the mouth), bone elsewhere;
//   mandible: ivory teeth, pink gums, bone elsewhere.
// Which vertex is tooth, gum or palate is decided by core/dentalShading.js.

import { BufferAttribute, Color } from 'three';
import { dentalWeights, palatalWeights } from '../core/dentalShading.js';
import { TISSUE_COLORS } from './materials.js';

/** Lower tooth tips lie from about 3 mm above to 6 mm below the upper ones (overbite, curve of Spee). */
const MANDIBLE_TIP_BAND = Object.freeze( [ - 3.5, 6 ] );

/** The lowest y of a geometry (the occlusal level of an upper jaw at rest). */
export function lowestY( geometry ) {

	geometry.computeBoundingBox();
	return geometry.boundingBox.min.y;

}

/** The attribute's components as a packed Float32Array (copies only if interleaved or typed otherwise). */
function packed( attribute ) {

	if ( attribute.array instanceof Float32Array && attribute.array.length === 3 * attribute.count && ! attribute.isInterleavedBufferAttribute ) return attribute.array;
	const out = new Float32Array( 3 * attribute.count );
	for ( let i = 0; i < attribute.count; i ++ ) {

		out[ 3 * i ] = attribute.getX( i );
		out[ 3 * i + 1 ] = attribute.getY( i );
		out[ 3 * i + 2 ] = attribute.getZ( i );

	}

	return out;

}

/**
 * Write a `color` attribute (linear RGB) on a maxilla or mandible geometry (which must have normals).
 * tissue: 'maxilla' (teeth point down) or 'mandible' (teeth point up); occlusalY: the occlusal
 * level (mm; for the maxilla, default its lowest point; required for the mandible).
 * Returns the vertex counts { teeth, gum, palate } with weight above one half, for reporting.
 */
export function colorJawVertices( geometry, tissue, { occlusalY } = {} ) {

	const positions = packed( geometry.getAttribute( 'position' ) );
	const n = positions.length / 3;
	const teeth = new Float32Array( n );
	const gum = new Float32Array( n );
	const palate = new Float32Array( n );
	const options = tissue === 'mandible' ? { upward: true, occlusalY, tipBand: MANDIBLE_TIP_BAND } : { occlusalY };
	if ( options.upward && occlusalY === undefined ) throw new Error( 'the mandible is coloured from the maxilla\'s occlusal level; load the maxilla' );
	dentalWeights( positions, options, teeth, gum );
	if ( tissue === 'maxilla' ) palatalWeights( positions, packed( geometry.getAttribute( 'normal' ) ), teeth, {}, palate );

	const bone = new Color( TISSUE_COLORS.bone );
	const pink = new Color( TISSUE_COLORS.gum );
	const ivory = new Color( TISSUE_COLORS.teeth );
	const colors = new Float32Array( 3 * n );
	const c = new Color();
	const counts = { teeth: 0, gum: 0, palate: 0 };
	for ( let i = 0; i < n; i ++ ) {

		c.copy( bone ).lerp( pink, Math.max( gum[ i ], palate[ i ] ) ).lerp( ivory, teeth[ i ] );
		colors[ 3 * i ] = c.r;
		colors[ 3 * i + 1 ] = c.g;
		colors[ 3 * i + 2 ] = c.b;
		if ( teeth[ i ] > 0.5 ) counts.teeth ++;
		if ( gum[ i ] > 0.5 ) counts.gum ++;
		if ( palate[ i ] > 0.5 && teeth[ i ] <= 0.5 ) counts.palate ++;

	}

	geometry.setAttribute( 'color', new BufferAttribute( colors, 3 ) );
	return counts;

}
