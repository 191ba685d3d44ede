// Section of a triangle mesh by a plane z = c: the line segments where its triangles cross the
// plane. The cutaway draws these as the outline of each cut tissue. Pure, allocation-free.
//
// Convention: a vertex with z - c >= 0 counts as on the kept side, z - c < 0 as cut away. A
// triangle crosses the plane when its vertices are not all on one side; it then has exactly two
// edges with ends on opposite sides, and the segment joins their crossing points. A vertex lying
// exactly on the plane therefore gives a zero-length segment or a segment through it, never a gap.

/**
 * Write the section segments of a mesh by the plane z = planeZ into `target`.
 *
 * positions: Float32Array or Float64Array (3 * vertexCount), x y z per vertex.
 * index: Uint16Array / Uint32Array (3 * triangleCount), or null for non-indexed positions.
 * target: Float32Array of at least 6 * triangleCount floats: x0 y0 z0 x1 y1 z1 per segment.
 * Returns the number of segments written.
 */
export function planeSectionSegments( positions, index, planeZ, target ) {

	const triangleCount = index ? index.length / 3 : positions.length / 9;
	if ( ! Number.isInteger( triangleCount ) ) throw new RangeError( 'index (or positions) length is not a multiple of 3 triangles' );

	let count = 0;
	for ( let t = 0; t < triangleCount; t ++ ) {

		const a = index ? index[ 3 * t ] : 3 * t;
		const b = index ? index[ 3 * t + 1 ] : 3 * t + 1;
		const c = index ? index[ 3 * t + 2 ] : 3 * t + 2;
		const da = positions[ 3 * a + 2 ] - planeZ;
		const db = positions[ 3 * b + 2 ] - planeZ;
		const dc = positions[ 3 * c + 2 ] - planeZ;
		const sa = da >= 0, sb = db >= 0, sc = dc >= 0;
		if ( sa === sb && sb === sc ) continue;

		if ( 6 * count + 6 > target.length ) throw new RangeError( `target holds ${ target.length / 6 } segments; the section needs more` );

		let o = 6 * count;
		if ( sa !== sb ) o = writeCrossing( positions, a, b, da, db, target, o );
		if ( sb !== sc ) o = writeCrossing( positions, b, c, db, dc, target, o );
		if ( sc !== sa ) writeCrossing( positions, c, a, dc, da, target, o );
		count ++;

	}

	return count;

}

/** Write the point where edge (i, j) crosses the plane, given signed distances di and dj. */
function writeCrossing( positions, i, j, di, dj, target, offset ) {

	const s = di / ( di - dj );
	for ( let k = 0; k < 3; k ++ ) {

		const pi = positions[ 3 * i + k ];
		target[ offset + k ] = pi + ( positions[ 3 * j + k ] - pi ) * s;

	}

	return offset + 3;

}
