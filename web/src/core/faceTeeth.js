// The labial faces of the incisors that the skin and lips may not pass: step 4 of the face rig
// (faceRig.js). Twin of server/glasshead/geometry/face_teeth.py; tests/vectors/face-rig.json keeps
// the two in agreement. Each row of incisors is a table of the rig definition, x = F( y, z ) on a
// regular grid, bilinear inside it and receding quadratically outside; a point behind the face
// (and less than `depth` behind it) is pushed out along its normal, `steps` times.
//
// Hot paths read everything from typed arrays and write moves as arithmetic rather than branches,
// so that the compiled code has seen every operation before its first frame (no garbage per pose).

/** Layout of a table's numbers (table.n, Float64Array), read by the per-vertex code. */
const T_Y0 = 0;
const T_Z0 = 1;
const T_STEP_Y = 2;
const T_STEP_Z = 3;
const T_ROWS = 4;
const T_COLS = 5;
const T_RECESSION = 6;
const T_DEPTH = 7;
const T_STEPS = 8;
const T_X_MAX = 9;

/**
 * A table of the definition (definition.teeth.upper or .lower) as typed arrays: values x and
 * numbers n (T_* layout), built once per rig.
 */
export function teethTable( table ) {

	const x = Float64Array.from( table.x );
	// The face never lies in front of its largest table value: a cheap exact early-out.
	const n = Float64Array.of( table.y0, table.z0, table.step_y, table.step_z, table.rows, table.cols, table.recession, table.depth ?? 0, table.steps ?? 0, Math.max( ...x ) );
	return { x, n };

}

const scratchBound = new Float64Array( 3 );
const scratchQuery = new Float64Array( 3 );

/**
 * The labial face x = F( y, z ) of a row of incisors (a table of the definition), bilinear in
 * its table, receding by recession * ( distance outside, mm )^2 beyond it; F, dF/dy and dF/dz
 * into target.
 */
export function teethBound( table, y, z, target ) {

	const { x, n } = teethTable( table );
	scratchQuery[ 1 ] = y;
	scratchQuery[ 2 ] = z;
	return teethBoundAt( x, n, scratchQuery, target );

}

/** teethBound() at the point p ( y = p[ 1 ], z = p[ 2 ] ) for table values x and numbers n. */
function teethBoundAt( x, n, p, target ) {

	const rows = n[ T_ROWS ];
	const cols = n[ T_COLS ];
	const stepY = n[ T_STEP_Y ];
	const stepZ = n[ T_STEP_Z ];
	const recession = n[ T_RECESSION ];
	const fy = ( p[ 1 ] - n[ T_Y0 ] ) / stepY;
	const fz = ( p[ 2 ] - n[ T_Z0 ] ) / stepZ;
	const cy = fy < 0 ? 0 : ( fy > rows - 1 ? rows - 1 : fy );
	const cz = fz < 0 ? 0 : ( fz > cols - 1 ? cols - 1 : fz );
	const iy = Math.min( Math.floor( cy ), rows - 2 );
	const iz = Math.min( Math.floor( cz ), cols - 2 );
	const ty = cy - iy;
	const tz = cz - iz;
	const v00 = x[ iy * cols + iz ];
	const v01 = x[ iy * cols + iz + 1 ];
	const v10 = x[ ( iy + 1 ) * cols + iz ];
	const v11 = x[ ( iy + 1 ) * cols + iz + 1 ];
	const low = ( 1 - tz ) * v00 + tz * v01;
	const high = ( 1 - tz ) * v10 + tz * v11;
	const outY = ( fy - cy ) * stepY;
	const outZ = ( fz - cz ) * stepZ;
	target[ 0 ] = ( 1 - ty ) * low + ty * high - recession * ( outY * outY + outZ * outZ );
	const left = ( 1 - ty ) * v00 + ty * v10;
	const right = ( 1 - ty ) * v01 + ty * v11;
	target[ 1 ] = ( outY === 0 ? ( high - low ) / stepY : 0 ) - 2 * recession * outY;
	target[ 2 ] = ( outZ === 0 ? ( right - left ) / stepZ : 0 ) - 2 * recession * outZ;
	return target;

}

/**
 * Push one point (in the table's frame, in p[ 0..2 ]) out of a face (values x, numbers n;
 * face_teeth.push_out);
 * returns 1 if it moved, else 0. Everything is read from typed arrays and the moves are written
 * as arithmetic rather than branches (a step that does not move adds 0): the compiled code has
 * seen every operation before its first frame.
 */
export function pushOut( x, n, p ) {

	let moved = 0;
	for ( let step = 0; step < n[ T_STEPS ]; step ++ ) {

		if ( inFront( n, p[ 0 ], p[ 1 ], p[ 2 ] ) ) break;
		teethBoundAt( x, n, p, scratchBound );
		const behind = scratchBound[ 0 ] - p[ 0 ];
		const hit = behind > 0 && behind < n[ T_DEPTH ] ? 1 : 0;
		const dy = scratchBound[ 1 ];
		const dz = scratchBound[ 2 ];
		const s = hit * behind / ( 1 + dy * dy + dz * dz );
		p[ 0 ] += s;
		p[ 1 ] -= s * dy;
		p[ 2 ] -= s * dz;
		moved |= hit;

	}

	return moved;

}

/**
 * Whether ( x, y, z ) lies in front of everything the face can be: F <= xMax - recession *
 * ( distance outside the table )^2, so most points need no lookup at all.
 */
function inFront( n, x, y, z ) {

	const fy = ( y - n[ T_Y0 ] ) / n[ T_STEP_Y ];
	const fz = ( z - n[ T_Z0 ] ) / n[ T_STEP_Z ];
	const outY = ( fy < 0 ? fy : ( fy > n[ T_ROWS ] - 1 ? fy - n[ T_ROWS ] + 1 : 0 ) ) * n[ T_STEP_Y ];
	const outZ = ( fz < 0 ? fz : ( fz > n[ T_COLS ] - 1 ? fz - n[ T_COLS ] + 1 : 0 ) ) * n[ T_STEP_Z ];
	return x >= n[ T_X_MAX ] - n[ T_RECESSION ] * ( outY * outY + outZ * outZ );

}

const scratchPoint = new Float64Array( 3 );

/**
 * Step 4 of the face rig for one mesh (face_teeth.clamp_to_teeth): its moving points pushed out
 * of the lower row in the rest mandible's frame, then out of the upper row. Returns how many
 * pushes moved a point.
 * @param {Uint32Array} moving vertices to test
 * @param {Float64Array} work posed positions, xyz per vertex, moved in place
 * @param {{ upper: object, lower: object }} teeth tables from teethTable()
 * @param {ArrayLike<number>} pose the jaw pose, row-major 3 x 4 (jaw.js jawPose())
 */
export function clampToTeeth( moving, work, teeth, pose ) {

	const p = scratchPoint;
	const lowerX = teeth.lower.x;
	const lowerN = teeth.lower.n;
	const upperX = teeth.upper.x;
	const upperN = teeth.upper.n;
	let count = 0;
	for ( let k = 0; k < moving.length; k ++ ) {

		const o = 3 * moving[ k ];
		// Rest mandible frame: R^T ( x - t ).
		const dx = work[ o ] - pose[ 3 ];
		const dy = work[ o + 1 ] - pose[ 7 ];
		const dz = work[ o + 2 ] - pose[ 11 ];
		const x = pose[ 0 ] * dx + pose[ 4 ] * dy + pose[ 8 ] * dz;
		const y = pose[ 1 ] * dx + pose[ 5 ] * dy + pose[ 9 ] * dz;
		const z = pose[ 2 ] * dx + pose[ 6 ] * dy + pose[ 10 ] * dz;
		// A point in front of a row is left alone, as pushOut() would leave it (most points).
		let lower = 0;
		if ( lowerN[ T_STEPS ] > 0 && ! inFront( lowerN, x, y, z ) ) {

			p[ 0 ] = x; p[ 1 ] = y; p[ 2 ] = z;
			lower = pushOut( lowerX, lowerN, p );
			// Back to the posed frame only when moved (lower = 1): a point left alone keeps its
			// exact coordinates, not their round trip.
			work[ o ] += lower * ( pose[ 0 ] * p[ 0 ] + pose[ 1 ] * p[ 1 ] + pose[ 2 ] * p[ 2 ] + pose[ 3 ] - work[ o ] );
			work[ o + 1 ] += lower * ( pose[ 4 ] * p[ 0 ] + pose[ 5 ] * p[ 1 ] + pose[ 6 ] * p[ 2 ] + pose[ 7 ] - work[ o + 1 ] );
			work[ o + 2 ] += lower * ( pose[ 8 ] * p[ 0 ] + pose[ 9 ] * p[ 1 ] + pose[ 10 ] * p[ 2 ] + pose[ 11 ] - work[ o + 2 ] );

		}

		let upper = 0;
		if ( upperN[ T_STEPS ] > 0 && ! inFront( upperN, work[ o ], work[ o + 1 ], work[ o + 2 ] ) ) {

			p[ 0 ] = work[ o ]; p[ 1 ] = work[ o + 1 ]; p[ 2 ] = work[ o + 2 ];
			upper = pushOut( upperX, upperN, p );
			work[ o ] = p[ 0 ]; work[ o + 1 ] = p[ 1 ]; work[ o + 2 ] = p[ 2 ];

		}

		count += lower + upper;

	}

	return count;

}

/**
 * Run pushOut on points in front of, just behind and far behind the middle of each table, so that
 * its compiled code starts from complete type feedback (faceRig.js primes the rest of the pose).
 */
export function primeTeeth( teeth ) {

	const p = new Float64Array( 3 );
	for ( const table of [ teeth.lower, teeth.upper ] ) {

		const { x, n } = table;
		const middle = Math.floor( n[ T_ROWS ] / 2 ) * n[ T_COLS ] + Math.floor( n[ T_COLS ] / 2 );
		const y = n[ T_Y0 ] + Math.floor( n[ T_ROWS ] / 2 ) * n[ T_STEP_Y ];
		const z = n[ T_Z0 ] + Math.floor( n[ T_COLS ] / 2 ) * n[ T_STEP_Z ];
		for ( const depth of [ - 1, 0.5, n[ T_DEPTH ] + 1, 0.5, - 1 ] ) {

			p[ 0 ] = x[ middle ] - depth; p[ 1 ] = y; p[ 2 ] = z;
			pushOut( x, n, p );

		}

	}

}
