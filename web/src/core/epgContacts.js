// Synthetic EPG contact, every frame: which electrodes the corrected tongue surface touches.
// Twin of server/glasshead/epg/contacts.py; tests/vectors/epg-contacts.json proves they agree.
//
// Each electrode has a probe: the segment along its normal n (toward the tongue) from `behind`
// mm behind it to `tolerance` mm in front of it. The electrode is contacted when a tongue
// triangle crosses its probe: the line E + t n hits it (two-sided Moller-Trumbore 1997, with
// the collision kernels' barycentric slack) at -behind <= t <= tolerance. The tongue has been
// corrected against the palate first, so a touching tongue lies on the palate's surface, where
// the electrodes are (Cohen, Beskow and Massaro 1998, part 6).
//
// The probes never move, so everything about them is built once (createContactModel): their
// boxes, the lowest height any of them reaches, and a uniform grid over them whose cells list
// the probes that cross them. Per frame (epgContacts), a triangle is skipped at once when all its
// corners are below every probe (most of the tongue); the others are boxed, looked up in the
// grid, and tested only against the few probes whose boxes meet theirs and that are not already
// contacted. Skipping never removes a triangle that could hit (boxes are widened by PAD_MM), so
// the answer is the brute force's, bit for bit: the arithmetic of the test is the Python twin's.

import { COLLISION_TOL, EPG_CONTACT_BEHIND_MM, EPG_CONTACT_TOLERANCE_MM } from './constants.js';

/** Barycentric slack of the probe test (the collision kernels' own). */
const SLACK = COLLISION_TOL.barycentric;
/** mm. Boxes are widened by this so the broad phase can never drop a hit the slack accepts. */
const PAD_MM = 1e-6;
/** mm. Edge of a cell of the probe grid: about two probes long. */
export const PROBE_CELL_MM = 3;

/**
 * Everything about one grid's probes that does not depend on the tongue, plus the scratch arrays
 * of epgContacts (so a frame allocates nothing).
 * @param {{grid: string, rows: number, columns: number, electrodes: Array<{id: string, cell: number, position: number[], normal: number[]}>}} grid
 *   one grid of the layout file (layout.grids.reading62, say)
 * @param {{tolerance?: number, behind?: number, cellSize?: number}} [options]
 */
export function createContactModel( grid, index, vertexCount, { tolerance = EPG_CONTACT_TOLERANCE_MM, behind = EPG_CONTACT_BEHIND_MM, cellSize = PROBE_CELL_MM } = {} ) {

	const electrodes = grid?.electrodes;
	if ( ! Array.isArray( electrodes ) || electrodes.length === 0 ) throw new RangeError( 'createContactModel: the grid has no electrodes' );
	if ( ! ( tolerance > 0 && behind >= 0 && cellSize > 0 ) ) throw new RangeError( 'createContactModel: need tolerance > 0, behind >= 0, cellSize > 0' );
	if ( ! ( index?.length >= 3 && index.length % 3 === 0 ) ) throw new RangeError( 'createContactModel: index must hold 3 vertex indices per triangle' );
	if ( ! ( Number.isInteger( vertexCount ) && vertexCount > 0 ) ) throw new RangeError( 'createContactModel: vertexCount must be a positive integer' );
	const count = electrodes.length;
	const cells = grid.rows * grid.columns;
	const origins = new Float64Array( 3 * count );
	const directions = new Float64Array( 3 * count );
	const cellOf = new Int32Array( count );
	const boxes = new Float64Array( 6 * count ); // min xyz, max xyz per probe
	const seen = new Uint8Array( cells );
	let yLow = Infinity;
	const lo = [ Infinity, Infinity, Infinity ], hi = [ - Infinity, - Infinity, - Infinity ];
	electrodes.forEach( ( e, k ) => {

		const p = e.position, n = e.normal;
		if ( ! ( p?.length === 3 && n?.length === 3 ) || ! [ ...p, ...n ].every( Number.isFinite ) ) throw new RangeError( `createContactModel: electrode ${e.id} needs a finite position and normal` );
		if ( Math.abs( Math.hypot( n[ 0 ], n[ 1 ], n[ 2 ] ) - 1 ) > 1e-6 ) throw new RangeError( `createContactModel: the normal of electrode ${e.id} is not a unit vector` );
		if ( ! Number.isInteger( e.cell ) || e.cell < 0 || e.cell >= cells || seen[ e.cell ] ) throw new RangeError( `createContactModel: electrode ${e.id} has a bad or repeated cell ${e.cell}` );
		seen[ e.cell ] = 1;
		cellOf[ k ] = e.cell;
		for ( let a = 0; a < 3; a ++ ) {

			origins[ 3 * k + a ] = p[ a ];
			directions[ 3 * k + a ] = n[ a ];
			const u = p[ a ] - behind * n[ a ], v = p[ a ] + tolerance * n[ a ];
			boxes[ 6 * k + a ] = Math.min( u, v ) - PAD_MM;
			boxes[ 6 * k + 3 + a ] = Math.max( u, v ) + PAD_MM;
			lo[ a ] = Math.min( lo[ a ], boxes[ 6 * k + a ] );
			hi[ a ] = Math.max( hi[ a ], boxes[ 6 * k + 3 + a ] );

		}

		yLow = Math.min( yLow, boxes[ 6 * k + 1 ] );

	} );

	// The probe grid: cell lists in CSR form (cellStart[c] .. cellStart[c + 1] in cellItems).
	const shape = lo.map( ( l, a ) => Math.max( 1, Math.ceil( ( hi[ a ] - l ) / cellSize ) ) );
	const gridCells = shape[ 0 ] * shape[ 1 ] * shape[ 2 ];
	const lists = Array.from( { length: gridCells }, () => [] );
	for ( let k = 0; k < count; k ++ ) {

		const range = [ 0, 1, 2 ].map( ( a ) => [
			Math.min( shape[ a ] - 1, Math.floor( ( boxes[ 6 * k + a ] - lo[ a ] ) / cellSize ) ),
			Math.min( shape[ a ] - 1, Math.floor( ( boxes[ 6 * k + 3 + a ] - lo[ a ] ) / cellSize ) ),
		] );
		for ( let i = range[ 0 ][ 0 ]; i <= range[ 0 ][ 1 ]; i ++ ) for ( let j = range[ 1 ][ 0 ]; j <= range[ 1 ][ 1 ]; j ++ ) for ( let l = range[ 2 ][ 0 ]; l <= range[ 2 ][ 1 ]; l ++ ) {

			lists[ ( i * shape[ 1 ] + j ) * shape[ 2 ] + l ].push( k );

		}

	}

	const cellStart = new Int32Array( gridCells + 1 );
	lists.forEach( ( list, c ) => {

		cellStart[ c + 1 ] = cellStart[ c ] + list.length;

	} );
	const cellItems = Int32Array.from( lists.flat() );

	// The triangles around each vertex (CSR), so a frame visits only triangles with a corner that
	// reaches the probes' height.
	const triangleCount = index.length / 3;
	const aroundStart = new Int32Array( vertexCount + 1 );
	for ( let m = 0; m < index.length; m ++ ) {

		if ( ! ( index[ m ] < vertexCount ) ) throw new RangeError( `createContactModel: index ${index[ m ]} is not a vertex (${vertexCount})` );
		aroundStart[ index[ m ] + 1 ] ++;

	}

	for ( let v = 0; v < vertexCount; v ++ ) aroundStart[ v + 1 ] += aroundStart[ v ];
	const around = new Int32Array( index.length );
	const fill = aroundStart.slice( 0, vertexCount );
	for ( let m = 0; m < index.length; m ++ ) around[ fill[ index[ m ] ] ++ ] = ( m / 3 ) | 0;

	return {
		index, vertexCount, triangleCount, aroundStart, around,
		triangleStamp: new Uint32Array( triangleCount ), stamp: 0,
		grid: grid.grid, rows: grid.rows, columns: grid.columns, cells, count,
		ids: Object.freeze( electrodes.map( ( e ) => e.id ) ),
		tolerance, behind, origins, directions, cellOf, boxes, yLow,
		gridMin: Float64Array.from( lo ), gridShape: Int32Array.from( shape ), invCell: 1 / cellSize,
		cellStart, cellItems,
		// Scratch: per-electrode contact and the last triangle tested against it.
		contacted: new Uint8Array( count ),
		lastTriangle: new Int32Array( count ),
	};

}

/**
 * Does the probe of electrode k cross the triangle whose corners start at positions[ a ], [ b ]
 * and [ c ]? Two-sided Moller-Trumbore, operation for operation as probe_hits in contacts.py.
 * (Offsets, not coordinates, are passed: integers travel unboxed, so a call allocates nothing.)
 */
function probeHits( model, k, positions, a, b, c ) {

	const ax = positions[ a ], ay = positions[ a + 1 ], az = positions[ a + 2 ];
	const bx = positions[ b ], by = positions[ b + 1 ], bz = positions[ b + 2 ];
	const cx = positions[ c ], cy = positions[ c + 1 ], cz = positions[ c + 2 ];
	const o = 3 * k;
	const dx = model.directions[ o ], dy = model.directions[ o + 1 ], dz = model.directions[ o + 2 ];
	const e1x = bx - ax, e1y = by - ay, e1z = bz - az;
	const e2x = cx - ax, e2y = cy - ay, e2z = cz - az;
	const hx = dy * e2z - dz * e2y;
	const hy = dz * e2x - dx * e2z;
	const hz = dx * e2y - dy * e2x;
	const det = e1x * hx + e1y * hy + e1z * hz;
	if ( det === 0 ) return false;
	const sx = model.origins[ o ] - ax, sy = model.origins[ o + 1 ] - ay, sz = model.origins[ o + 2 ] - az;
	const inv = 1 / det;
	const u = ( sx * hx + sy * hy + sz * hz ) * inv;
	if ( ! ( u >= - SLACK ) ) return false;
	const qx = sy * e1z - sz * e1y;
	const qy = sz * e1x - sx * e1z;
	const qz = sx * e1y - sy * e1x;
	const v = ( dx * qx + dy * qy + dz * qz ) * inv;
	if ( ! ( v >= - SLACK ) || ! ( u + v <= 1 + SLACK ) ) return false;
	const t = ( e2x * qx + e2y * qy + e2z * qz ) * inv;
	return t >= - model.behind && t <= model.tolerance;

}

/**
 * Contacts of the tongue `positions` (xyz per vertex, corrected) with triangles `index`.
 * Writes target[ cell ] = 1 for each contacted electrode and 0 elsewhere (target holds
 * rows * columns cells, row-major, R1 first: for the Reading palate the 64-cell frame of
 * epgIndices.js, its R1 corners always 0). Returns the number of contacted electrodes.
 * Allocates nothing.
 * @param {object} model from createContactModel
 * @param {Float32Array|Float64Array} positions
 * @param {Uint32Array|Uint16Array|Int32Array} index 3 vertex indices per triangle
 * @param {Uint8Array} target
 * @returns {number}
 */
export function epgContacts( model, positions, target ) {

	const contacted = model.contacted, last = model.lastTriangle;
	contacted.fill( 0 );
	last.fill( - 1 );
	const index = model.index, aroundStart = model.aroundStart, around = model.around;
	const triangleStamp = model.triangleStamp;
	if ( model.stamp === 0xFFFFFFFF ) {

		triangleStamp.fill( 0 );
		model.stamp = 0;

	}

	const stamp = ++ model.stamp;
	const yLow = model.yLow, boxes = model.boxes;
	const gx = model.gridMin[ 0 ], gy = model.gridMin[ 1 ], gz = model.gridMin[ 2 ];
	const nx = model.gridShape[ 0 ], ny = model.gridShape[ 1 ], nz = model.gridShape[ 2 ];
	const inv = model.invCell, start = model.cellStart, items = model.cellItems;
	const maxX = gx + nx / inv, maxY = gy + ny / inv, maxZ = gz + nz / inv;
	let found = 0;

	for ( let vertex = 0; vertex < model.vertexCount; vertex ++ ) {

		// A triangle with every corner below every probe cannot reach one.
		if ( positions[ 3 * vertex + 1 ] < yLow ) continue;
		for ( let r = aroundStart[ vertex ], rEnd = aroundStart[ vertex + 1 ]; r < rEnd; r ++ ) {

			const triangle = around[ r ];
			if ( triangleStamp[ triangle ] === stamp ) continue;
			triangleStamp[ triangle ] = stamp;
			const t = 3 * triangle;
			const a = 3 * index[ t ], b = 3 * index[ t + 1 ], c = 3 * index[ t + 2 ];
			const ax = positions[ a ], ay = positions[ a + 1 ], az = positions[ a + 2 ];
			const bx = positions[ b ], by = positions[ b + 1 ], bz = positions[ b + 2 ];
			const cx = positions[ c ], cy = positions[ c + 1 ], cz = positions[ c + 2 ];
			const x0 = ax < bx ? ( ax < cx ? ax : cx ) : ( bx < cx ? bx : cx );
			const x1 = ax > bx ? ( ax > cx ? ax : cx ) : ( bx > cx ? bx : cx );
			if ( x1 < gx || x0 > maxX ) continue;
			const z0 = az < bz ? ( az < cz ? az : cz ) : ( bz < cz ? bz : cz );
			const z1 = az > bz ? ( az > cz ? az : cz ) : ( bz > cz ? bz : cz );
			if ( z1 < gz || z0 > maxZ ) continue;
			const y0 = ay < by ? ( ay < cy ? ay : cy ) : ( by < cy ? by : cy );
			const y1 = ay > by ? ( ay > cy ? ay : cy ) : ( by > cy ? by : cy );
			if ( y0 > maxY ) continue;
			const i0 = x0 > gx ? ( ( x0 - gx ) * inv ) | 0 : 0, i1 = Math.min( nx - 1, ( ( x1 - gx ) * inv ) | 0 );
			const j0 = y0 > gy ? ( ( y0 - gy ) * inv ) | 0 : 0, j1 = Math.min( ny - 1, ( ( y1 - gy ) * inv ) | 0 );
			const l0 = z0 > gz ? ( ( z0 - gz ) * inv ) | 0 : 0, l1 = Math.min( nz - 1, ( ( z1 - gz ) * inv ) | 0 );
			for ( let i = i0; i <= i1; i ++ ) for ( let j = j0; j <= j1; j ++ ) for ( let l = l0; l <= l1; l ++ ) {

				const cell = ( i * ny + j ) * nz + l;
				for ( let m = start[ cell ], end = start[ cell + 1 ]; m < end; m ++ ) {

					const k = items[ m ];
					if ( contacted[ k ] === 1 || last[ k ] === triangle ) continue;
					last[ k ] = triangle;
					const box = 6 * k;
					if ( x1 < boxes[ box ] || x0 > boxes[ box + 3 ] || y1 < boxes[ box + 1 ] || y0 > boxes[ box + 4 ] || z1 < boxes[ box + 2 ] || z0 > boxes[ box + 5 ] ) continue;
					if ( probeHits( model, k, positions, a, b, c ) ) {

						contacted[ k ] = 1;
						found ++;

					}

				}

			}

		}

	}

	target.fill( 0, 0, model.cells );
	const cellOf = model.cellOf;
	for ( let k = 0; k < model.count; k ++ ) if ( contacted[ k ] === 1 ) target[ cellOf[ k ] ] = 1;
	return found;

}

/**
 * The same contacts by testing every probe against every triangle: the slow reference (and the
 * benchmark's baseline). Allocates nothing.
 */
export function epgContactsBruteForce( model, positions, target ) {

	const index = model.index;
	target.fill( 0, 0, model.cells );
	let found = 0;
	for ( let k = 0; k < model.count; k ++ ) {

		for ( let t = 0; t < index.length; t += 3 ) {

			const a = 3 * index[ t ], b = 3 * index[ t + 1 ], c = 3 * index[ t + 2 ];
			if ( probeHits( model, k, positions, a, b, c ) ) {

				target[ model.cellOf[ k ] ] = 1;
				found ++;
				break;

			}

		}

	}

	return found;

}

/** Contacts as emuR-style rows: `rows` strings of '0'/'1', row 1 (front) first. */
export function contactRows( model, frame ) {

	const rows = [];
	for ( let r = 0; r < model.rows; r ++ ) {

		let row = '';
		for ( let c = 0; c < model.columns; c ++ ) row += frame[ r * model.columns + c ] ? '1' : '0';
		rows.push( row );

	}

	return rows;

}
