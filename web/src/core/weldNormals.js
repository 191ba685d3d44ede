// Smooth shading across the seam between separate meshes that share boundary vertices (the face
// skin and the head shell meet along the skin's rim): vertices of different meshes at the same
// position get the average of their normals, so no crease shows where the meshes meet.

/**
 * Average the normals of coincident vertices across meshes, in place.
 *
 * meshes: array of { positions: Float32Array (3n), normals: Float32Array (3n) }.
 * tolerance: mm; positions are matched on a grid of this size (same cell = same point).
 * Returns the number of vertices whose normal changed (those shared by two or more meshes).
 * Allocates a Map for the matching: a load-time step, not a per-frame one.
 */
export function weldNormals( meshes, tolerance = 1e-3 ) {

	if ( ! ( tolerance > 0 ) ) throw new RangeError( `tolerance must be positive, got ${ tolerance }` );
	const key = ( p, i ) => `${ Math.round( p[ 3 * i ] / tolerance ) },${ Math.round( p[ 3 * i + 1 ] / tolerance ) },${ Math.round( p[ 3 * i + 2 ] / tolerance ) }`;

	// First pass: which positions occur in more than one mesh.
	const owners = new Map();
	meshes.forEach( ( { positions, normals }, m ) => {

		if ( positions.length !== normals.length ) throw new RangeError( `mesh ${ m }: normals must match positions` );
		for ( let i = 0; i < positions.length / 3; i ++ ) {

			const k = key( positions, i );
			const entry = owners.get( k );
			if ( ! entry ) owners.set( k, { mesh: m, shared: false, sum: null } );
			else if ( entry.mesh !== m ) entry.shared = true;

		}

	} );

	// Second pass: sum the normals of shared positions, third: write the normalised sums back.
	for ( const { positions, normals } of meshes ) {

		for ( let i = 0; i < positions.length / 3; i ++ ) {

			const entry = owners.get( key( positions, i ) );
			if ( ! entry.shared ) continue;
			entry.sum ??= [ 0, 0, 0 ];
			for ( let k = 0; k < 3; k ++ ) entry.sum[ k ] += normals[ 3 * i + k ];

		}

	}

	let changed = 0;
	for ( const { positions, normals } of meshes ) {

		for ( let i = 0; i < positions.length / 3; i ++ ) {

			const entry = owners.get( key( positions, i ) );
			if ( ! entry.shared ) continue;
			const [ x, y, z ] = entry.sum;
			const length = Math.hypot( x, y, z );
			if ( length === 0 ) continue;
			normals[ 3 * i ] = x / length;
			normals[ 3 * i + 1 ] = y / length;
			normals[ 3 * i + 2 ] = z / length;
			changed ++;

		}

	}

	return changed;

}
