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
// the probes that cross them. Per frame (electrodeContacts), only triangles with a corner at or above
// that height are visited (through the triangles around each vertex); each corner is placed in
// the grid once per frame, a triangle whose corners all lie beyond one side of the grid is
// skipped, and the others are tested only against the probes listed in the cells they span,
// not yet contacted, whose boxes meet theirs. Skipping never removes a triangle that could hit
// (boxes are widened by PAD_MM), so the answer is the brute force's, bit for bit: the arithmetic
// of the test is the Python twin's.

import { COLLISION_TOL, EPG_CONTACT_BEHIND_MM, EPG_CONTACT_TOLERANCE_MM } from './constants.js';

/** Barycentric slack of the probe test (the collision kernels' own). */
const SLACK = COLLISION_TOL.barycentric;
/** mm. Boxes are widened by this so the broad phase can never drop a hit the slack accepts. */
const PAD_MM = 1e-6;
/** mm. Edge of a cell of the probe grid: about two probes long. */
export const PROBE_CELL_MM = 3;

/**
 * Everything about one grid's probes that does not depend on the tongue, plus the scratch arrays
 * of electrodeContacts (so a frame allocates nothing).
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
	// One cell more than the probes need, so that every probe box ends strictly inside the grid:
	// a point in no cell along an axis is then beyond every probe on that axis.
	const shape = lo.map( ( l, a ) => Math.max( 1, Math.ceil( ( hi[ a ] - l ) / cellSize ) ) + 1 );
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
		// Per vertex and frame: its grid cell (clamped to the grid) and which sides of the grid
		// it is beyond (bits: x low, x high, y low, y high, z low, z high), when vertexStamp matches.
		vertexStamp: new Uint32Array( vertexCount ),
		vertexCell: new Int32Array( 3 * vertexCount ),
		vertexOut: new Uint8Array( vertexCount ),
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
export function electrodeContacts( model, positions, target ) {

	const contacted = model.contacted, last = model.lastTriangle;
	contacted.fill( 0 );
	last.fill( - 1 );
	const index = model.index, aroundStart = model.aroundStart, around = model.around;
	const triangleStamp = model.triangleStamp, vertexStamp = model.vertexStamp;
	if ( model.stamp === 0xFFFFFFFF ) {

		triangleStamp.fill( 0 );
		vertexStamp.fill( 0 );
		model.stamp = 0;

	}

	const stamp = ++ model.stamp;
	const yLow = model.yLow, boxes = model.boxes;
	const cellOfVertex = model.vertexCell, out = model.vertexOut;
	const start = model.cellStart, items = model.cellItems;
	const ny = model.gridShape[ 1 ], nz = model.gridShape[ 2 ];
	let found = 0;

	for ( let vertex = 0; vertex < model.vertexCount; vertex ++ ) {

		// A triangle with every corner below every probe cannot reach one: start from the corners
		// that are not.
		if ( positions[ 3 * vertex + 1 ] < yLow ) continue;
		for ( let r = aroundStart[ vertex ], rEnd = aroundStart[ vertex + 1 ]; r < rEnd; r ++ ) {

			const triangle = around[ r ];
			if ( triangleStamp[ triangle ] === stamp ) continue;
			triangleStamp[ triangle ] = stamp;
			const t = 3 * triangle;
			const va = index[ t ], vb = index[ t + 1 ], vc = index[ t + 2 ];
			if ( vertexStamp[ va ] !== stamp ) placeVertex( model, positions, va, stamp );
			if ( vertexStamp[ vb ] !== stamp ) placeVertex( model, positions, vb, stamp );
			if ( vertexStamp[ vc ] !== stamp ) placeVertex( model, positions, vc, stamp );
			if ( ( out[ va ] & out[ vb ] & out[ vc ] ) !== 0 ) continue; // all beyond one side of the grid
			const a3 = 3 * va, b3 = 3 * vb, c3 = 3 * vc;
			const ia = cellOfVertex[ a3 ], ib = cellOfVertex[ b3 ], ic = cellOfVertex[ c3 ];
			const ja = cellOfVertex[ a3 + 1 ], jb = cellOfVertex[ b3 + 1 ], jc = cellOfVertex[ c3 + 1 ];
			const la = cellOfVertex[ a3 + 2 ], lb = cellOfVertex[ b3 + 2 ], lc = cellOfVertex[ c3 + 2 ];
			const i0 = ia < ib ? ( ia < ic ? ia : ic ) : ( ib < ic ? ib : ic ), i1 = ia > ib ? ( ia > ic ? ia : ic ) : ( ib > ic ? ib : ic );
			const j0 = ja < jb ? ( ja < jc ? ja : jc ) : ( jb < jc ? jb : jc ), j1 = ja > jb ? ( ja > jc ? ja : jc ) : ( jb > jc ? jb : jc );
			const l0 = la < lb ? ( la < lc ? la : lc ) : ( lb < lc ? lb : lc ), l1 = la > lb ? ( la > lc ? la : lc ) : ( lb > lc ? lb : lc );
			let boxReady = false;
			let x0 = 0, x1 = 0, y0 = 0, y1 = 0, z0 = 0, z1 = 0;
			for ( let i = i0; i <= i1; i ++ ) for ( let j = j0; j <= j1; j ++ ) for ( let l = l0; l <= l1; l ++ ) {

				const cell = ( i * ny + j ) * nz + l;
				for ( let m = start[ cell ], end = start[ cell + 1 ]; m < end; m ++ ) {

					const k = items[ m ];
					if ( contacted[ k ] === 1 || last[ k ] === triangle ) continue;
					last[ k ] = triangle;
					if ( ! boxReady ) {

						const ax = positions[ a3 ], ay = positions[ a3 + 1 ], az = positions[ a3 + 2 ];
						const bx = positions[ b3 ], by = positions[ b3 + 1 ], bz = positions[ b3 + 2 ];
						const cx = positions[ c3 ], cy = positions[ c3 + 1 ], cz = positions[ c3 + 2 ];
						x0 = ax < bx ? ( ax < cx ? ax : cx ) : ( bx < cx ? bx : cx ); x1 = ax > bx ? ( ax > cx ? ax : cx ) : ( bx > cx ? bx : cx );
						y0 = ay < by ? ( ay < cy ? ay : cy ) : ( by < cy ? by : cy ); y1 = ay > by ? ( ay > cy ? ay : cy ) : ( by > cy ? by : cy );
						z0 = az < bz ? ( az < cz ? az : cz ) : ( bz < cz ? bz : cz ); z1 = az > bz ? ( az > cz ? az : cz ) : ( bz > cz ? bz : cz );
						boxReady = true;

					}

					const box = 6 * k;
					if ( x1 < boxes[ box ] || x0 > boxes[ box + 3 ] || y1 < boxes[ box + 1 ] || y0 > boxes[ box + 4 ] || z1 < boxes[ box + 2 ] || z0 > boxes[ box + 5 ] ) continue;
					if ( probeHits( model, k, positions, a3, b3, c3 ) ) {

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
 * Grid cell of a vertex (clamped into the grid) and the sides of the grid it lies beyond, for
 * this frame. A triangle whose corners all lie beyond one side meets no probe box; otherwise the
 * clamped cells of its corners span every cell its box meets.
 */
function placeVertex( model, positions, v, stamp ) {

	const o = 3 * v;
	const inv = model.invCell, min = model.gridMin, shape = model.gridShape;
	const i = Math.floor( ( positions[ o ] - min[ 0 ] ) * inv );
	const j = Math.floor( ( positions[ o + 1 ] - min[ 1 ] ) * inv );
	const l = Math.floor( ( positions[ o + 2 ] - min[ 2 ] ) * inv );
	const nx = shape[ 0 ], ny = shape[ 1 ], nz = shape[ 2 ];
	model.vertexOut[ v ] = ( i < 0 ? 1 : 0 ) | ( i >= nx ? 2 : 0 ) | ( j < 0 ? 4 : 0 ) | ( j >= ny ? 8 : 0 ) | ( l < 0 ? 16 : 0 ) | ( l >= nz ? 32 : 0 );
	const cells = model.vertexCell;
	cells[ o ] = i < 0 ? 0 : ( i >= nx ? nx - 1 : i );
	cells[ o + 1 ] = j < 0 ? 0 : ( j >= ny ? ny - 1 : j );
	cells[ o + 2 ] = l < 0 ? 0 : ( l >= nz ? nz - 1 : l );
	model.vertexStamp[ v ] = stamp;

}

/**
 * The same contacts by testing every probe against every triangle: the slow reference (and the
 * benchmark's baseline). Allocates nothing.
 */
export function electrodeContactsBruteForce( model, positions, target ) {

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
