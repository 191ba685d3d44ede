// The collision liner drawn as a wireframe of its longitude and latitude lines (the paper's
// Figure 2): the first-hit points of the rays cast from O, joined along every few grid lines.
// Where a ray missed the maxilla (radius +inf) the line breaks.

import { BufferAttribute, BufferGeometry, LineBasicMaterial, LineSegments } from 'three';

/** Draw every n-th grid line: every 6 at the 0.5 degree step is a 3 degree wireframe. */
export const LINER_LINE_EVERY = 6;

export const LINER_COLOR = '#1d5f8c';

/** The wireframe sits this far (mm) in front of the palate as seen from O, so the palate cannot hide it. */
export const LINER_LIFT_MM = 0.3;

/**
 * Segments of the liner's longitude and latitude lines (Float32Array, x y z x y z per segment,
 * project frame, mm).
 * theta = lon0 + i step (0: superior, +90 deg: anterior), phi = lat0 + j step (+: the left);
 * direction ( cos phi sin theta, cos phi cos theta, sin phi ); node ( j, i ) at radius
 * nodeRadius[ j * ( nlon + 1 ) + i ] from O, less `lift`. Only segments whose two nodes were hit are kept.
 * @param {object} tables from decodeCollisionTables()
 * @param {number} every draw every n-th line of each family
 * @param {number} lift mm toward O (so that the palate does not hide the lines drawn on it)
 */
export function linerSegments( tables, every = LINER_LINE_EVERY, lift = LINER_LIFT_MM ) {

	if ( ! Number.isInteger( every ) || every < 1 ) throw new RangeError( `every must be a positive integer, got ${ every }` );
	const { nlon, nlat, lon0, lat0, step, nodeRadius, origin } = tables;
	const columns = nlon + 1;
	const node = ( j, i, out, o ) => {

		const r = nodeRadius[ j * columns + i ] - lift;
		const theta = lon0 + i * step;
		const phi = lat0 + j * step;
		out[ o ] = origin[ 0 ] + r * Math.cos( phi ) * Math.sin( theta );
		out[ o + 1 ] = origin[ 1 ] + r * Math.cos( phi ) * Math.cos( theta );
		out[ o + 2 ] = origin[ 2 ] + r * Math.sin( phi );

	};

	const hit = ( j, i ) => Number.isFinite( nodeRadius[ j * columns + i ] );
	const pairs = [];
	for ( let j = 0; j <= nlat; j += every ) {

		for ( let i = 0; i < nlon; i ++ ) if ( hit( j, i ) && hit( j, i + 1 ) ) pairs.push( j, i, j, i + 1 );

	}

	for ( let i = 0; i <= nlon; i += every ) {

		for ( let j = 0; j < nlat; j ++ ) if ( hit( j, i ) && hit( j + 1, i ) ) pairs.push( j, i, j + 1, i );

	}

	const segments = new Float32Array( 3 * pairs.length / 2 );
	for ( let k = 0; k < pairs.length; k += 2 ) node( pairs[ k ], pairs[ k + 1 ], segments, 3 * k / 2 );
	return segments;

}

/** The wireframe as a three.js object (hidden until shown). */
export class LinerWireframe extends LineSegments {

	constructor( tables, { every = LINER_LINE_EVERY, color = LINER_COLOR } = {} ) {

		const geometry = new BufferGeometry();
		geometry.setAttribute( 'position', new BufferAttribute( linerSegments( tables, every ), 3 ) );
		super( geometry, new LineBasicMaterial( { color, transparent: true, opacity: 0.9 } ) );
		this.name = 'collision-liner';
		this.renderOrder = 6;
		this.visible = false;

	}

	get segmentCount() {

		return this.geometry.getAttribute( 'position' ).count / 2;

	}

	dispose() {

		this.geometry.dispose();
		this.material.dispose();
		this.removeFromParent();

	}

}
