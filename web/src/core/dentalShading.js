// Which vertices of a jaw mesh belong to the teeth, by a height rule. The maxilla and mandible each
// come as one mesh (bone or palate plus teeth), so the browser colours them per vertex.
//
// The rule, for the upper jaw (mirror it for the lower jaw by `upward: true`):
//   - the occlusal level is `occlusalY`, by default the lowest point of the mesh (the cusp tips
//     and incisal edges of the upper teeth). The mandible's highest points are its condyles, not
//     its teeth, so it is given the maxilla's occlusal level (the teeth meet at rest);
//   - for each vertex, its "column" is the set of vertices within about `radius` mm of it in the
//     horizontal (x, z) plane, and the column's tip is the lowest vertex in it;
//   - a column carries a tooth when its tip's depth below the occlusal level lies in `tipBand`
//     (this excludes the palatal vault, the ramus, the condyles and the inner face of the chin);
//   - in such a column, vertices up to `crownHeight` mm above the tip are tooth crown, with a
//     linear blend of `blend` mm; a band of `gumHeight` mm above the crown is gum.
// Heights are along +y (superior) in the project frame, in millimetres.
// Crown heights: about 7.5 (molars) to 10.5 mm (upper central incisors), Ash & Nelson, Wheeler's
// Dental Anatomy, tables of crown dimensions.

export const DENTAL_DEFAULTS = Object.freeze( {
	radius: 3, // mm, horizontal reach of a column
	tipBand: Object.freeze( [ - 1, 4.5 ] ), // mm, tip depth range of a tooth column
	crownHeight: 8.5, // mm
	blend: 1.2, // mm
	gumHeight: 3.5, // mm
} );

/**
 * Per-vertex tooth and gum weights in [0, 1].
 *
 * positions: Float32Array (3 * n) in the project frame (mm).
 * options: { upward: false for the upper jaw (teeth point down), true for the lower jaw;
 *   occlusalY: the occlusal level (mm), default the extreme vertex } plus any of DENTAL_DEFAULTS.
 * teeth, gum: Float32Array (n) written with the weights.
 * Allocates a spatial hash once per call (load time, not per frame).
 */
export function dentalWeights( positions, options, teeth, gum ) {

	const { upward = false, occlusalY, radius, tipBand, crownHeight, blend, gumHeight } = { ...DENTAL_DEFAULTS, ...options };
	const n = positions.length / 3;
	if ( ! Number.isInteger( n ) ) throw new RangeError( 'positions length must be a multiple of 3' );
	if ( teeth.length < n || gum.length < n ) throw new RangeError( `teeth and gum need ${ n } entries` );
	if ( ! ( radius > 0 && crownHeight > 0 && blend >= 0 && gumHeight >= 0 && tipBand[ 0 ] <= tipBand[ 1 ] ) ) {

		throw new RangeError( 'radius and crownHeight must be positive, blend and gumHeight non-negative, tipBand ordered' );

	}

	// Work with "depth into the jaw" h: h = y for the upper jaw (teeth at the bottom), h = -y for
	// the lower jaw, so the tips are always the smallest h.
	const sign = upward ? - 1 : 1;
	let minX = Infinity, minZ = Infinity, maxX = - Infinity, maxZ = - Infinity;
	for ( let i = 0; i < n; i ++ ) {

		const x = positions[ 3 * i ], z = positions[ 3 * i + 2 ];
		minX = Math.min( minX, x ); maxX = Math.max( maxX, x );
		minZ = Math.min( minZ, z ); maxZ = Math.max( maxZ, z );

	}

	// Lowest h per grid cell of size `radius`; a column is the 3 x 3 cells around a vertex.
	const nx = Math.max( 1, Math.ceil( ( maxX - minX ) / radius ) + 1 );
	const nz = Math.max( 1, Math.ceil( ( maxZ - minZ ) / radius ) + 1 );
	const cellTip = new Float64Array( nx * nz ).fill( Infinity );
	const cellOf = new Int32Array( n );
	for ( let i = 0; i < n; i ++ ) {

		const cx = Math.floor( ( positions[ 3 * i ] - minX ) / radius );
		const cz = Math.floor( ( positions[ 3 * i + 2 ] - minZ ) / radius );
		const cell = cx * nz + cz;
		cellOf[ i ] = cell;
		cellTip[ cell ] = Math.min( cellTip[ cell ], sign * positions[ 3 * i + 1 ] );

	}

	let occlusal = Infinity;
	if ( occlusalY === undefined ) {

		for ( let i = 0; i < n; i ++ ) occlusal = Math.min( occlusal, sign * positions[ 3 * i + 1 ] );

	} else occlusal = sign * occlusalY;
	for ( let i = 0; i < n; i ++ ) {

		const cx = Math.floor( cellOf[ i ] / nz ), cz = cellOf[ i ] % nz;
		let tip = Infinity;
		for ( let dx = - 1; dx <= 1; dx ++ ) {

			for ( let dz = - 1; dz <= 1; dz ++ ) {

				const x = cx + dx, z = cz + dz;
				if ( x >= 0 && x < nx && z >= 0 && z < nz ) tip = Math.min( tip, cellTip[ x * nz + z ] );

			}

		}

		const height = sign * positions[ 3 * i + 1 ] - tip;
		if ( tip - occlusal < tipBand[ 0 ] || tip - occlusal > tipBand[ 1 ] ) {

			teeth[ i ] = 0;
			gum[ i ] = 0;
			continue;

		}

		teeth[ i ] = rampDown( height, crownHeight - blend / 2, crownHeight + blend / 2 );
		gum[ i ] = ( 1 - teeth[ i ] ) * rampDown( height, crownHeight + gumHeight - blend / 2, crownHeight + gumHeight + blend / 2 );

	}

}

/** 1 below a, 0 above b, linear between. */
function rampDown( value, a, b ) {

	if ( value <= a ) return 1;
	if ( value >= b ) return 0;
	return ( b - value ) / ( b - a );

}

export const PALATE_DEFAULTS = Object.freeze( {
	slab: 4, // mm, depth (along x) of the slabs in which the arch width is measured
	margin: 1.5, // mm the palate must lie inside the inner edge of the teeth
	maxHeight: 30, // mm above the occlusal level; higher surfaces are the nasal side
	maxNormalY: 0.25, // a palatal surface faces the mouth: its normal does not point up
} );

/**
 * Per-vertex weights (0 or 1) of the palate of an upper jaw: the surface inside the dental arch
 * that faces down into the mouth.
 *
 * The arch's inner half-width at each depth x is the smallest |z| of the tooth vertices
 * (teeth weight > 0.5) in that slab of x; behind the last slab with teeth the last width holds,
 * ahead of the first the first. A vertex is palatal when |z| is at least `margin` inside it, its
 * height is within `maxHeight` of the occlusal level and its normal's y is at most `maxNormalY`.
 *
 * positions, normals: Float32Array (3 * n), project frame. teeth: Float32Array (n) from
 * dentalWeights. target: Float32Array (n), written with 0 or 1.
 */
export function palatalWeights( positions, normals, teeth, options, target ) {

	const { slab, margin, maxHeight, maxNormalY } = { ...PALATE_DEFAULTS, ...options };
	const n = positions.length / 3;
	if ( normals.length !== positions.length || teeth.length < n || target.length < n ) {

		throw new RangeError( 'normals must match positions; teeth and target need one entry per vertex' );

	}

	let minX = Infinity, maxX = - Infinity, occlusal = Infinity;
	for ( let i = 0; i < n; i ++ ) {

		minX = Math.min( minX, positions[ 3 * i ] );
		maxX = Math.max( maxX, positions[ 3 * i ] );
		occlusal = Math.min( occlusal, positions[ 3 * i + 1 ] );

	}

	const slabs = Math.max( 1, Math.ceil( ( maxX - minX ) / slab ) + 1 );
	const inner = new Float64Array( slabs ).fill( Infinity );
	for ( let i = 0; i < n; i ++ ) {

		if ( teeth[ i ] <= 0.5 ) continue;
		const k = Math.floor( ( positions[ 3 * i ] - minX ) / slab );
		inner[ k ] = Math.min( inner[ k ], Math.abs( positions[ 3 * i + 2 ] ) );

	}

	// Fill slabs without teeth from their neighbours: forward, then backward.
	let last = Infinity;
	for ( let k = 0; k < slabs; k ++ ) {

		if ( inner[ k ] === Infinity ) inner[ k ] = last;
		else last = inner[ k ];

	}

	last = Infinity;
	for ( let k = slabs - 1; k >= 0; k -- ) {

		if ( inner[ k ] === Infinity ) inner[ k ] = last;
		else last = inner[ k ];

	}

	for ( let i = 0; i < n; i ++ ) {

		const k = Math.floor( ( positions[ 3 * i ] - minX ) / slab );
		const inside = Math.abs( positions[ 3 * i + 2 ] ) <= inner[ k ] - margin;
		const low = positions[ 3 * i + 1 ] - occlusal <= maxHeight;
		const facesMouth = normals[ 3 * i + 1 ] <= maxNormalY;
		target[ i ] = inside && low && facesMouth ? 1 : 0;

	}

}
