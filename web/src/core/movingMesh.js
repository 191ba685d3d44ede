// Per-frame upkeep of a mesh of which only some vertices move (the face rig moves about a third
// of the face's vertices, fewer of the head shell's): the vertex normals and the bounding sphere,
// redone only where the moving vertices reach. A triangle with no moving corner adds the same to
// its corners every frame, so its share of their normal sums is kept from rest. The normals are
// those of meshVolume.vertexNormals() up to the order of summation. Nothing here allocates but
// movingMesh(), once.

import { addTriangleNormals } from './meshVolume.js';

/**
 * Split a mesh for partial updates (once).
 * @param {Float32Array|Float64Array} positions rest positions, xyz per vertex
 * @param {Uint32Array} index triangles
 * @param {Uint32Array} moving the vertices that can move (all others keep their rest position)
 * @param {ArrayLike<number>} extra vertices whose normals are rewritten with the others (the
 *   seam that weldSeam() overwrites, so that it starts from their own normals each frame)
 * @returns {object} for updateNormals() and enclose(): triangles (those with a moving corner),
 *   vertices (their corners and `extra`), fixed (3 sums per entry of vertices: the other
 *   triangles' share), sums (scratch, 3 per mesh vertex), moving, still (largest squared
 *   distance of a still vertex from the centre) and centre (of the rest mesh's bounding box)
 */
export function movingMesh( positions, index, moving, extra = [] ) {

	const count = positions.length / 3;
	const moves = new Uint8Array( count );
	for ( const v of moving ) moves[ v ] = 1;
	const corners = [];
	const fixedTriangles = [];
	for ( let t = 0; t < index.length; t += 3 ) {

		const list = moves[ index[ t ] ] || moves[ index[ t + 1 ] ] || moves[ index[ t + 2 ] ] ? corners : fixedTriangles;
		list.push( index[ t ], index[ t + 1 ], index[ t + 2 ] );

	}

	const triangles = Uint32Array.from( corners );
	const vertices = Uint32Array.from( new Set( [ ...corners, ...extra ] ) ).sort();
	const sums = new Float64Array( 3 * count );
	addTriangleNormals( positions, Uint32Array.from( fixedTriangles ), sums );
	const fixed = new Float64Array( 3 * vertices.length );
	vertices.forEach( ( v, k ) => fixed.set( sums.subarray( 3 * v, 3 * v + 3 ), 3 * k ) );

	const low = [ Infinity, Infinity, Infinity ];
	const high = [ - Infinity, - Infinity, - Infinity ];
	for ( let i = 0; i < positions.length; i ++ ) {

		low[ i % 3 ] = Math.min( low[ i % 3 ], positions[ i ] );
		high[ i % 3 ] = Math.max( high[ i % 3 ], positions[ i ] );

	}

	const centre = Float64Array.from( low, ( value, i ) => ( value + high[ i ] ) / 2 );
	let still = 0;
	for ( let v = 0; v < count; v ++ ) if ( ! moves[ v ] ) still = Math.max( still, distanceSq( positions, 3 * v, centre ) );
	return { triangles, vertices, fixed, sums, moving: Uint32Array.from( moving ), still, centre };

}

function distanceSq( positions, o, centre ) {

	const dx = positions[ o ] - centre[ 0 ];
	const dy = positions[ o + 1 ] - centre[ 1 ];
	const dz = positions[ o + 2 ] - centre[ 2 ];
	return dx * dx + dy * dy + dz * dz;

}

/**
 * Unit vertex normals of the posed mesh into target, written only for mesh.vertices (the others
 * keep what they hold: their rest normals).
 * @param {object} mesh from movingMesh()
 * @param {Float32Array|Float64Array} positions posed positions
 * @param {Float32Array|Float64Array} target normals, xyz per vertex
 */
export function updateNormals( mesh, positions, target ) {

	const { vertices, fixed, sums } = mesh;
	for ( let k = 0; k < vertices.length; k ++ ) {

		const o = 3 * vertices[ k ];
		sums[ o ] = fixed[ 3 * k ];
		sums[ o + 1 ] = fixed[ 3 * k + 1 ];
		sums[ o + 2 ] = fixed[ 3 * k + 2 ];

	}

	addTriangleNormals( positions, mesh.triangles, sums );
	for ( let k = 0; k < vertices.length; k ++ ) {

		const o = 3 * vertices[ k ];
		const length = Math.sqrt( sums[ o ] * sums[ o ] + sums[ o + 1 ] * sums[ o + 1 ] + sums[ o + 2 ] * sums[ o + 2 ] );
		const scale = length > 0 ? 1 / length : 0;
		target[ o ] = sums[ o ] * scale;
		target[ o + 1 ] = sums[ o + 1 ] * scale;
		target[ o + 2 ] = sums[ o + 2 ] * scale;

	}

	return target;

}

/**
 * A sphere (three.js Sphere, or { center, radius }) about the fixed centre enclosing the posed
 * mesh: the still vertices' radius is known, so only the moving ones are measured.
 * @param {object} mesh from movingMesh()
 * @param {Float32Array|Float64Array} positions posed positions
 * @param {{ center: { set: Function }, radius: number }} sphere written
 */
export function enclose( mesh, positions, sphere ) {

	const { moving, centre } = mesh;
	let farthest = mesh.still;
	for ( let k = 0; k < moving.length; k ++ ) {

		const d = distanceSq( positions, 3 * moving[ k ], centre );
		if ( d > farthest ) farthest = d;

	}

	sphere.center.set( centre[ 0 ], centre[ 1 ], centre[ 2 ] );
	// A hair more than the farthest vertex: float32 rounding must not leave a vertex outside.
	sphere.radius = Math.sqrt( farthest ) * ( 1 + 1e-6 ) + 1e-6;
	return sphere;

}
