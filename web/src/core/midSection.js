// The mid-sagittal section of one mesh as polylines, recut every frame without allocating: the
// flat diagram of the vocal tract and the constriction read it. Pure; never imports three.js.
//
// A triangle crosses z = 0 when its vertices are not all on one side (z >= 0 is the kept side,
// as in section.js). Its two crossing edges give a segment. Two triangles that share an edge
// share its crossing point, so the segments are joined by edge: each crossing is keyed by its
// edge (lower vertex index, higher vertex index) in an open-addressing table that is emptied by
// bumping a generation stamp rather than by clearing. The crossing is computed from the lower
// vertex index, so both triangles of an edge write the same numbers. A vertex lying exactly on
// the plane may split a chain there (the edges through it differ); nothing is lost.
//
// Most frames move no vertex across the plane (the tongue's and the lips' midline vertices stay on
// it), so each vertex's side is kept: when no side changed, last frame's crossing triangles are
// this frame's, and only they are recut. Only the vertices the index uses are read.
//
// The pose of a part that moves rigidly in its plane (the jaw: a rotation about a z-parallel axis
// and a slide in x y) maps the cut points, so a rigid part is cut once and only mapped per frame.

/** Numbers in a pose: a row-major 3 x 4 matrix [ R | t ] (core/jaw.js). */
export const POSE_LENGTH = 3 * 4;

/** A pose whose rotation or translation leaves the plane by more than this is not planar. */
export const PLANAR_TOLERANCE = 1e-9;

const EMPTY = - 1;

/** Segments per chunk of a chain; each chunk has a bounding box, for the constriction's search. */
export const CHUNK_SEGMENTS = 8;

/**
 * A part's section buffers, sized once for its triangles.
 * @param {Uint16Array|Uint32Array} index three vertex indices per triangle
 * @param {number} vertexCount vertices of the part
 */
export function createSectionPart( index, vertexCount ) {

	if ( ! index || index.length % 3 !== 0 ) throw new RangeError( 'a section part needs an index of three vertices per triangle' );
	if ( ! ( vertexCount > 0 ) || vertexCount * vertexCount > 2 ** 31 ) throw new RangeError( `vertexCount ${ vertexCount } is out of range` );
	const triangles = index.length / 3;
	const ends = 2 * triangles; // two crossing points per segment, at most one segment per triangle
	let size = 16;
	while ( size < 2 * ends ) size *= 2;
	const used = new Uint8Array( vertexCount );
	for ( let k = 0; k < index.length; k ++ ) used[ index[ k ] ] = 1;
	return {
		index,
		vertexCount,
		/** The vertices the index uses, and each one's side of the plane (1: z >= 0) when last cut. */
		vertices: Uint32Array.from( { length: vertexCount }, ( _, v ) => v ).filter( ( v ) => used[ v ] ),
		sides: new Uint8Array( vertexCount ),
		/** The first index of each triangle that crossed the plane when last cut (-1: never cut). */
		crossing: new Int32Array( triangles ),
		crossingCount: - 1,
		/** Crossing point of each segment end (x y), end e = 2 * segment + 0 or 1. */
		ends: new Float64Array( 2 * ends ),
		/** The end sharing an edge with each end, or EMPTY. */
		link: new Int32Array( ends ),
		seen: new Int32Array( ends ),
		keys: new Int32Array( size ),
		values: new Int32Array( size ),
		stamps: new Int32Array( size ),
		mask: size - 1,
		generation: 0,
		segmentCount: 0,
		/** The polylines in the part's own frame: x y per point (the first pointCount points). */
		local: new Float64Array( 2 * ends ),
		/** The polylines posed (the pose of cutSection or posePoints): x y per point. */
		points: new Float64Array( 2 * ends ),
		pointCount: 0,
		/** Chain k is points starts[ k ] to starts[ k + 1 ] - 1; closed[ k ] is 1 for a loop. */
		starts: new Int32Array( ends + 1 ),
		closed: new Uint8Array( ends ),
		chainCount: 0,
		/** Chunks of CHUNK_SEGMENTS segments of one chain: min x, min y, max x, max y (posed). */
		boxes: new Float64Array( 4 * ( ends + 1 ) ),
		/** Chain and first segment of each chunk. */
		chunkChain: new Int32Array( ends + 1 ),
		chunkFirst: new Int32Array( ends + 1 ),
		chunkCount: 0,
		/** Scratch of the constriction's search: the chunks near a chunk of another part. */
		near: new Int32Array( ends + 1 ),
		nearCount: 0,
	};

}

/** Whether a pose (row-major 3 x 4) keeps z = 0 on itself and moves only within it. */
export function isPlanarPose( pose ) {

	return Math.abs( pose[ 2 ] ) < PLANAR_TOLERANCE && Math.abs( pose[ 6 ] ) < PLANAR_TOLERANCE &&
		Math.abs( pose[ 8 ] ) < PLANAR_TOLERANCE && Math.abs( pose[ 9 ] ) < PLANAR_TOLERANCE &&
		Math.abs( pose[ 10 ] - 1 ) < PLANAR_TOLERANCE && Math.abs( pose[ 11 ] ) < PLANAR_TOLERANCE;

}

/**
 * Cut the part's mesh at z = 0 and join the segments into polylines (part.local), then map them
 * by `pose` into part.points (identity when null). Returns the number of points.
 * @param {object} part from createSectionPart
 * @param {Float32Array|Float64Array} positions x y z per vertex, the part's frame
 * @param {Float64Array|null} pose planar row-major 3 x 4 (isPlanarPose), or null
 */
export function cutSection( part, positions, pose = null ) {

	if ( positions.length < 3 * part.vertexCount ) throw new RangeError( `positions hold ${ positions.length / 3 } vertices; the part has ${ part.vertexCount }` );
	const { index, vertices, sides, crossing } = part;
	part.generation ++;
	let changed = part.crossingCount < 0 ? 1 : 0;
	for ( let k = 0; k < vertices.length; k ++ ) {

		const v = vertices[ k ];
		const side = positions[ 3 * v + 2 ] >= 0 ? 1 : 0;
		changed |= side ^ sides[ v ];
		sides[ v ] = side;

	}

	if ( changed ) {

		let crossed = 0;
		for ( let t = 0; t < index.length; t += 3 ) {

			const up = sides[ index[ t ] ] + sides[ index[ t + 1 ] ] + sides[ index[ t + 2 ] ];
			if ( up !== 0 && up !== 3 ) crossing[ crossed ++ ] = t;

		}

		part.crossingCount = crossed;

	}

	let count = 0;
	for ( let k = 0; k < part.crossingCount; k ++ ) {

		const t = crossing[ k ];
		const a = index[ t ], b = index[ t + 1 ], c = index[ t + 2 ];
		const sa = sides[ a ], sb = sides[ b ], sc = sides[ c ];
		let end = 2 * count;
		if ( sa !== sb ) end = cross( part, positions, a, b, end );
		if ( sb !== sc ) end = cross( part, positions, b, c, end );
		if ( sc !== sa ) cross( part, positions, c, a, end );
		count ++;

	}

	part.segmentCount = count;
	let points = 0;
	let chains = 0;
	const { seen, link, starts } = part;
	const generation = part.generation;
	// Open chains from a free end first; what is left is loops.
	for ( let e = 0; e < 2 * count; e ++ ) if ( seen[ e ] !== generation && link[ e ] === EMPTY ) points = walk( part, e, chains ++, points );
	for ( let e = 0; e < 2 * count; e ++ ) if ( seen[ e ] !== generation ) points = walk( part, e, chains ++, points );
	starts[ chains ] = points;
	part.pointCount = points;
	part.chainCount = chains;
	posePoints( part, pose );
	return points;

}

/** Write the crossing of edge (i, j) as segment end `end`, link it by its edge, return the next end. */
function cross( part, p, i, j, end ) {

	const { ends, link, keys, values, stamps, mask, generation } = part;
	const lo = i < j ? i : j, hi = i < j ? j : i;
	const zl = p[ 3 * lo + 2 ];
	const s = zl / ( zl - p[ 3 * hi + 2 ] );
	ends[ 2 * end ] = p[ 3 * lo ] + ( p[ 3 * hi ] - p[ 3 * lo ] ) * s;
	ends[ 2 * end + 1 ] = p[ 3 * lo + 1 ] + ( p[ 3 * hi + 1 ] - p[ 3 * lo + 1 ] ) * s;
	link[ end ] = EMPTY;
	const key = lo * part.vertexCount + hi;
	let slot = ( Math.imul( key, 0x9e3779b1 ) >>> 7 ) & mask;
	while ( stamps[ slot ] === generation ) {

		if ( keys[ slot ] === key ) {

			const other = values[ slot ];
			link[ end ] = other;
			link[ other ] = end;
			return end + 1;

		}

		slot = ( slot + 1 ) & mask;

	}

	stamps[ slot ] = generation;
	keys[ slot ] = key;
	values[ slot ] = end;
	return end + 1;

}

/** Walk chain number `chain` from segment end `start`, writing its points from `points` on; returns the next point. */
function walk( part, start, chain, points ) {

	const { ends, link, seen, local, starts, closed } = part;
	const generation = part.generation;
	starts[ chain ] = points;
	closed[ chain ] = 0;
	local[ 2 * points ] = ends[ 2 * start ];
	local[ 2 * points + 1 ] = ends[ 2 * start + 1 ];
	points ++;
	for ( let current = start; ; ) {

		const far = current ^ 1;
		seen[ current ] = generation;
		seen[ far ] = generation;
		const next = link[ far ];
		if ( next === start ) {

			closed[ chain ] = 1;
			return points;

		}

		local[ 2 * points ] = ends[ 2 * far ];
		local[ 2 * points + 1 ] = ends[ 2 * far + 1 ];
		points ++;
		if ( next === EMPTY || seen[ next ] === generation ) return points;
		current = next;

	}

}

/**
 * Map the part's local polylines by a planar pose into part.points (a copy when null); a rigid
 * part is cut once and posed every frame. Returns the part.
 */
export function posePoints( part, pose = null ) {

	const { local, points } = part;
	const n = part.pointCount;
	if ( ! pose ) {

		points.set( local.subarray( 0, 2 * n ) );

	} else {

		if ( ! isPlanarPose( pose ) ) throw new RangeError( 'the pose moves the part out of the mid-sagittal plane; cut posed positions instead' );
		for ( let k = 0; k < n; k ++ ) {

			const x = local[ 2 * k ], y = local[ 2 * k + 1 ];
			points[ 2 * k ] = pose[ 0 ] * x + pose[ 1 ] * y + pose[ 3 ];
			points[ 2 * k + 1 ] = pose[ 4 ] * x + pose[ 5 ] * y + pose[ 7 ];

		}

	}

	return chunkBoxes( part );

}

/** The number of segments of chain c: a loop closes on its first point; a lone point is one. */
export function chainSegmentCount( part, c ) {

	const n = part.starts[ c + 1 ] - part.starts[ c ];
	return part.closed[ c ] === 1 ? n : Math.max( n - 1, n > 0 ? 1 : 0 );

}

/** The bounding box of every chunk of CHUNK_SEGMENTS segments of each chain (posed points). */
function chunkBoxes( part ) {

	const { points, starts, boxes, chunkChain, chunkFirst } = part;
	let chunks = 0;
	for ( let c = 0; c < part.chainCount; c ++ ) {

		const first = starts[ c ];
		const n = starts[ c + 1 ] - first;
		const segments = chainSegmentCount( part, c );
		for ( let s0 = 0; s0 < segments; s0 += CHUNK_SEGMENTS ) {

			let x0 = Infinity, y0 = Infinity, x1 = - Infinity, y1 = - Infinity;
			const last = Math.min( s0 + CHUNK_SEGMENTS, segments );
			for ( let k = s0; k <= last; k ++ ) {

				const o = 2 * ( first + ( k % n ) );
				const x = points[ o ], y = points[ o + 1 ];
				if ( x < x0 ) x0 = x;
				if ( y < y0 ) y0 = y;
				if ( x > x1 ) x1 = x;
				if ( y > y1 ) y1 = y;

			}

			boxes[ 4 * chunks ] = x0;
			boxes[ 4 * chunks + 1 ] = y0;
			boxes[ 4 * chunks + 2 ] = x1;
			boxes[ 4 * chunks + 3 ] = y1;
			chunkChain[ chunks ] = c;
			chunkFirst[ chunks ] = s0;
			chunks ++;

		}

	}

	part.chunkCount = chunks;
	return part;

}

/** The pose of a three.js Matrix4's elements (column-major 4 x 4) as row-major 3 x 4, into target. */
export function poseFromMatrix( elements, target ) {

	for ( let row = 0; row < 3; row ++ ) for ( let column = 0; column < 4; column ++ ) target[ 4 * row + column ] = elements[ 4 * column + row ];
	return target;

}
