// Openings of a surface mesh (eyes and nostrils in the face skin) and the dome-shaped patches that
// close them. Pure functions over typed arrays; they run once when the skin loads.

/**
 * The boundary loops of a triangle mesh: chains of edges used by only one triangle.
 *
 * index: Uint16Array / Uint32Array (3 * m). Returns an array of loops, each an array of vertex ids
 * in the direction the edges run in their triangles (so a patch that closes the loop runs the
 * other way). Open chains (at non-manifold vertices) are returned as they are found.
 */
export function boundaryLoops( index ) {

	if ( index.length % 3 !== 0 ) throw new RangeError( 'index length must be a multiple of 3' );
	const edges = new Set();
	const key = ( a, b ) => a * 4294967296 + b;
	for ( let t = 0; t < index.length; t += 3 ) {

		for ( let k = 0; k < 3; k ++ ) edges.add( key( index[ t + k ], index[ t + ( k + 1 ) % 3 ] ) );

	}

	// Boundary half-edges: a -> b whose twin b -> a is missing.
	const next = new Map();
	for ( let t = 0; t < index.length; t += 3 ) {

		for ( let k = 0; k < 3; k ++ ) {

			const a = index[ t + k ], b = index[ t + ( k + 1 ) % 3 ];
			if ( ! edges.has( key( b, a ) ) ) {

				if ( ! next.has( a ) ) next.set( a, [] );
				next.get( a ).push( b );

			}

		}

	}

	const loops = [];
	for ( const start of next.keys() ) {

		while ( next.get( start ).length > 0 ) {

			const loop = [ start ];
			let current = next.get( start ).pop();
			while ( current !== start ) {

				loop.push( current );
				const outgoing = next.get( current );
				if ( ! outgoing || outgoing.length === 0 ) break;
				current = outgoing.pop();

			}

			loops.push( loop );

		}

	}

	return loops;

}

/**
 * Centre, unit normal and size of a loop of vertices.
 * The normal is Newell's (Graphics Gems III, "Newell's method for a plane equation"), reversed so
 * that it points the way the mesh's own normals point next to the opening.
 * Returns { centre: [x, y, z], normal: [x, y, z], meanRadius, perimeter, minZ, maxZ }.
 */
export function loopFrame( positions, loop ) {

	const n = loop.length;
	const centre = [ 0, 0, 0 ];
	let minZ = Infinity, maxZ = - Infinity;
	for ( const v of loop ) {

		for ( let k = 0; k < 3; k ++ ) centre[ k ] += positions[ 3 * v + k ] / n;
		minZ = Math.min( minZ, positions[ 3 * v + 2 ] );
		maxZ = Math.max( maxZ, positions[ 3 * v + 2 ] );

	}

	const normal = [ 0, 0, 0 ];
	let meanRadius = 0, perimeter = 0;
	for ( let i = 0; i < n; i ++ ) {

		const a = 3 * loop[ i ], b = 3 * loop[ ( i + 1 ) % n ];
		const [ ax, ay, az ] = [ positions[ a ], positions[ a + 1 ], positions[ a + 2 ] ];
		const [ bx, by, bz ] = [ positions[ b ], positions[ b + 1 ], positions[ b + 2 ] ];
		normal[ 0 ] += ( ay - by ) * ( az + bz );
		normal[ 1 ] += ( az - bz ) * ( ax + bx );
		normal[ 2 ] += ( ax - bx ) * ( ay + by );
		meanRadius += Math.hypot( ax - centre[ 0 ], ay - centre[ 1 ], az - centre[ 2 ] ) / n;
		perimeter += Math.hypot( bx - ax, by - ay, bz - az );

	}

	// The loop runs with the mesh's edges; a patch closing it runs against them, so its outward
	// normal is the reverse of the loop's own.
	const length = Math.hypot( ...normal ) || 1;
	for ( let k = 0; k < 3; k ++ ) normal[ k ] = - normal[ k ] / length;
	return { centre, normal, meanRadius, perimeter, minZ, maxZ };

}

/**
 * A patch closing `loop`: `rings` rings of vertices from the loop in to its centre, lifted along the
 * frame's normal by `bulge` * (1 - s^2) mm at fraction s of the way out (a dome; negative bulge
 * makes a dimple). Triangles are wound like the mesh around the opening.
 *
 * Returns { positions: Float32Array (3 * v), index: Uint32Array, coords: Float32Array (3 * v) } where
 * coords hold, per vertex, its offset from the centre in mm along two in-plane axes (u toward +y
 * where possible) and s (0 at the centre, 1 on the loop).
 */
export function domePatch( positions, loop, frame, { rings = 8, bulge = 0 } = {} ) {

	if ( ! Number.isInteger( rings ) || rings < 1 ) throw new RangeError( `rings must be a positive integer, got ${ rings }` );
	const n = loop.length;
	const count = 1 + rings * n;
	const out = new Float32Array( 3 * count );
	const coords = new Float32Array( 3 * count );
	const { centre, normal } = frame;

	// In-plane axes: u is the world up (+y) made perpendicular to the normal, v = normal x u.
	let u = [ - normal[ 1 ] * normal[ 0 ], 1 - normal[ 1 ] * normal[ 1 ], - normal[ 1 ] * normal[ 2 ] ];
	if ( Math.hypot( ...u ) < 1e-6 ) u = [ 1 - normal[ 0 ] * normal[ 0 ], - normal[ 0 ] * normal[ 1 ], - normal[ 0 ] * normal[ 2 ] ];
	const ul = Math.hypot( ...u );
	u = u.map( ( c ) => c / ul );
	const v = [
		normal[ 1 ] * u[ 2 ] - normal[ 2 ] * u[ 1 ],
		normal[ 2 ] * u[ 0 ] - normal[ 0 ] * u[ 2 ],
		normal[ 0 ] * u[ 1 ] - normal[ 1 ] * u[ 0 ],
	];

	const write = ( slot, s, p ) => {

		const lift = bulge * ( 1 - s * s );
		let du = 0, dv = 0;
		for ( let k = 0; k < 3; k ++ ) {

			const q = centre[ k ] + ( p[ k ] - centre[ k ] ) * s;
			out[ 3 * slot + k ] = q + normal[ k ] * lift;
			du += ( q - centre[ k ] ) * u[ k ];
			dv += ( q - centre[ k ] ) * v[ k ];

		}

		coords[ 3 * slot ] = du;
		coords[ 3 * slot + 1 ] = dv;
		coords[ 3 * slot + 2 ] = s;

	};

	write( 0, 0, centre );
	for ( let r = 1; r <= rings; r ++ ) {

		for ( let i = 0; i < n; i ++ ) {

			const p = [ positions[ 3 * loop[ i ] ], positions[ 3 * loop[ i ] + 1 ], positions[ 3 * loop[ i ] + 2 ] ];
			write( 1 + ( r - 1 ) * n + i, r / rings, p );

		}

	}

	// Ring r, vertex i is slot 1 + (r - 1) n + i; the loop runs a -> b in the mesh, so patch
	// triangles run b -> a.
	const index = new Uint32Array( 3 * n * ( 2 * rings - 1 ) );
	let t = 0;
	const slot = ( r, i ) => ( r === 0 ? 0 : 1 + ( r - 1 ) * n + ( i % n ) );
	for ( let i = 0; i < n; i ++ ) {

		index.set( [ slot( 1, i + 1 ), slot( 1, i ), 0 ], t );
		t += 3;
		for ( let r = 2; r <= rings; r ++ ) {

			index.set( [ slot( r, i + 1 ), slot( r, i ), slot( r - 1, i ) ], t );
			index.set( [ slot( r, i + 1 ), slot( r - 1, i ), slot( r - 1, i + 1 ) ], t + 3 );
			t += 6;

		}

	}

	return { positions: out, index, coords };

}
