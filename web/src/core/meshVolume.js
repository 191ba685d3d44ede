// Mesh helpers over flat typed arrays (twin of server/glasshead/geometry/mesh_volume.py): the
// area-weighted vertex normals and the enclosed volume of a closed triangle mesh. Positions are xyz
// per vertex, triangles an index of 3 vertices each, wound counter-clockwise seen from outside.
// Nothing here allocates: the tongue, the articulation and the face recompute normals every frame.

/** Unit vectors from sums (xyz per vertex) into target; a zero sum gives ( 0, 0, 0 ). */
function normalise( sums, target ) {

	for ( let v = 0; v < sums.length; v += 3 ) {

		// Math.sqrt, not Math.hypot: hypot guards against overflow we cannot have and is far slower.
		const length = Math.sqrt( sums[ v ] * sums[ v ] + sums[ v + 1 ] * sums[ v + 1 ] + sums[ v + 2 ] * sums[ v + 2 ] );
		const scale = length > 0 ? 1 / length : 0;
		target[ v ] = sums[ v ] * scale;
		target[ v + 1 ] = sums[ v + 1 ] * scale;
		target[ v + 2 ] = sums[ v + 2 ] * scale;

	}

	return target;

}

/**
 * Area-weighted unit vertex normals (mesh_volume.vertex_normals): each triangle adds
 * ( b - a ) x ( c - a ) to its corners.
 * @param {Float32Array|Float64Array} positions xyz per vertex
 * @param {Uint32Array} index
 * @param {Float64Array} sums scratch, same length as positions
 * @param {Float32Array|Float64Array} target normals, same length as positions
 * @returns target
 */
export function vertexNormals( positions, index, sums, target ) {

	sums.fill( 0 );
	addTriangleNormals( positions, index, sums );

	return normalise( sums, target );

}

/**
 * Signed volume, mm^3, of a closed mesh wound counter-clockwise from outside, by the divergence
 * theorem: the sum over triangles of a . ( b x c ) / 6 (mesh_volume.mesh_volume).
 * @param {Float32Array|Float64Array} positions
 * @param {Uint32Array} index
 * @returns {number}
 */
export function meshVolume( positions, index ) {

	let sum = 0;
	for ( let t = 0; t < index.length; t += 3 ) {

		const a = 3 * index[ t ];
		const b = 3 * index[ t + 1 ];
		const c = 3 * index[ t + 2 ];
		const bx = positions[ b ], by = positions[ b + 1 ], bz = positions[ b + 2 ];
		const cx = positions[ c ], cy = positions[ c + 1 ], cz = positions[ c + 2 ];
		sum += positions[ a ] * ( by * cz - bz * cy ) + positions[ a + 1 ] * ( bz * cx - bx * cz ) + positions[ a + 2 ] * ( bx * cy - by * cx );

	}

	return sum / 6;

}

/**
 * Each triangle adds ( b - a ) x ( c - a ) (twice its area along its normal) to the sums of its
 * corners: the accumulation of vertexNormals(), for callers that keep part of the sums.
 * @param {Float32Array|Float64Array} positions xyz per vertex
 * @param {Uint32Array|number[]} index triangles
 * @param {Float64Array} sums xyz per vertex, added to
 */
export function addTriangleNormals( positions, index, sums ) {

	for ( let t = 0; t < index.length; t += 3 ) {

		const a = 3 * index[ t ];
		const b = 3 * index[ t + 1 ];
		const c = 3 * index[ t + 2 ];
		const ux = positions[ b ] - positions[ a ];
		const uy = positions[ b + 1 ] - positions[ a + 1 ];
		const uz = positions[ b + 2 ] - positions[ a + 2 ];
		const vx = positions[ c ] - positions[ a ];
		const vy = positions[ c + 1 ] - positions[ a + 1 ];
		const vz = positions[ c + 2 ] - positions[ a + 2 ];
		const nx = uy * vz - uz * vy;
		const ny = uz * vx - ux * vz;
		const nz = ux * vy - uy * vx;
		sums[ a ] += nx; sums[ a + 1 ] += ny; sums[ a + 2 ] += nz;
		sums[ b ] += nx; sums[ b + 1 ] += ny; sums[ b + 2 ] += nz;
		sums[ c ] += nx; sums[ c + 1 ] += ny; sums[ c + 2 ] += nz;

	}

}
