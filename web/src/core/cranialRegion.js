// The cranial cavity on the cutting plane, from the cranium mesh. Pure; runs once when the
// cranium is loaded (it allocates its results).
//
// The cranium of the data is not a closed skull: it is one sheet, a band round the sides and the
// back of the head (about 47 to 105 mm high), open above (no vault), below (no skull base) and in
// front (the face). Its section by z = 0 is only a short line at the occiput; it bounds nothing
// by itself. What it does bound is the space between its two side walls: a point of the plane
// lies in the cranial cavity when the kept half's wall stands beside it. That region, seen square
// on, is enclosed by the kept half's rim (the band's upper, front and lower edges, projected onto
// the plane) and closed at the back by the band's own section (the occipital bone). Above and
// below the band the data has no bone, so the region stops at its rims.

import { planeSectionSegments } from './section.js';
import { chainSegments } from './sectionPolygon.js';

/**
 * The boundary loops of a triangle mesh: the edges used by one triangle only, walked into loops.
 * @returns {number[][]} vertex indices per loop, in walking order (longest loop first)
 */
export function boundaryLoops( index ) {

	const uses = new Map();
	const key = ( a, b ) => ( a < b ? `${ a },${ b }` : `${ b },${ a }` );
	for ( let t = 0; t < index.length; t += 3 ) {

		for ( let e = 0; e < 3; e ++ ) {

			const k = key( index[ t + e ], index[ t + ( e + 1 ) % 3 ] );
			uses.set( k, ( uses.get( k ) ?? 0 ) + 1 );

		}

	}

	const neighbours = new Map();
	for ( const [ k, count ] of uses ) {

		if ( count !== 1 ) continue;
		const [ a, b ] = k.split( ',' ).map( Number );
		if ( ! neighbours.has( a ) ) neighbours.set( a, [] );
		if ( ! neighbours.has( b ) ) neighbours.set( b, [] );
		neighbours.get( a ).push( b );
		neighbours.get( b ).push( a );

	}

	const seen = new Set();
	const loops = [];
	for ( const start of neighbours.keys() ) {

		if ( seen.has( start ) ) continue;
		const loop = [ start ];
		seen.add( start );
		for ( let current = start; ; ) {

			const next = neighbours.get( current ).find( ( n ) => ! seen.has( n ) );
			if ( next === undefined ) break;
			seen.add( next );
			loop.push( next );
			current = next;

		}

		loops.push( loop );

	}

	return loops.sort( ( a, b ) => b.length - a.length );

}

/**
 * The run of a closed loop of points (x y z per point) on the kept side (z >= 0), projected onto
 * z = 0: x y pairs, from where the loop enters the kept side to where it leaves it, the two ends
 * interpolated onto the plane. Null when the loop does not cross the plane exactly twice.
 */
function keptRun( xyz ) {

	const n = xyz.length / 3;
	const kept = ( k ) => xyz[ 3 * ( ( k + n ) % n ) + 2 ] >= 0;
	const entries = [];
	for ( let k = 0; k < n; k ++ ) if ( kept( k ) && ! kept( k - 1 ) ) entries.push( k );
	if ( entries.length !== 1 ) return null;
	const crossing = ( a, b ) => {

		const pa = 3 * ( ( a + n ) % n ), pb = 3 * ( ( b + n ) % n );
		const s = xyz[ pa + 2 ] / ( xyz[ pa + 2 ] - xyz[ pb + 2 ] );
		return [ xyz[ pa ] + s * ( xyz[ pb ] - xyz[ pa ] ), xyz[ pa + 1 ] + s * ( xyz[ pb + 1 ] - xyz[ pa + 1 ] ) ];

	};

	const start = entries[ 0 ];
	const run = [ ...crossing( start - 1, start ) ];
	let k = start;
	for ( ; kept( k ); k ++ ) run.push( xyz[ 3 * ( k % n ) ], xyz[ 3 * ( k % n ) + 1 ] );
	run.push( ...crossing( k - 1, k ) );
	return run;

}

const distance2 = ( p, i, q, j ) => ( p[ i ] - q[ j ] ) ** 2 + ( p[ i + 1 ] - q[ j + 1 ] ) ** 2;

/**
 * The cranial cavity's region on z = 0 (see the top of this file).
 * @param {Float32Array|Float64Array} positions x y z per vertex (the cranium, head frame, mm)
 * @param {Uint16Array|Uint32Array|number[]} index three vertices per triangle
 * @returns {{ outline: Float64Array, bone: Float64Array }|null} outline: x y per point, closed
 *   implicitly; bone: the part of it that is the cranium's own section (x y per point, an open
 *   chain; empty when the band does not cross the plane); null when the mesh has no boundary
 *   loop with one run on the kept side (e.g. a closed mesh: its section is then its region)
 */
export function cranialRegion( positions, index ) {

	const loop = boundaryLoops( index )[ 0 ];
	if ( ! loop ) return null;
	const xyz = new Float64Array( 3 * loop.length );
	loop.forEach( ( v, k ) => xyz.set( [ positions[ 3 * v ], positions[ 3 * v + 1 ], positions[ 3 * v + 2 ] ], 3 * k ) );
	const run = keptRun( xyz );
	if ( ! run ) return null;

	// The band's own section joins the run's two ends (the rim meets the plane at its ends).
	const segments = new Float32Array( 6 * index.length / 3 );
	const count = planeSectionSegments( positions, index, 0, segments );
	const chains = chainSegments( segments, count ).filter( ( chain ) => ! chain.closed );
	let bone = new Float64Array( 0 );
	if ( chains.length > 0 ) {

		const chain = chains.sort( ( a, b ) => b.points.length - a.points.length )[ 0 ].points;
		const last = run.length - 2, end = chain.length - 2;
		// Walk the chain from the run's last point back to its first.
		const forward = distance2( run, last, chain, 0 ) + distance2( run, 0, chain, end );
		const backward = distance2( run, last, chain, end ) + distance2( run, 0, chain, 0 );
		bone = Float64Array.from( chain );
		if ( backward < forward ) {

			for ( let k = 0; k < chain.length / 2; k ++ ) {

				bone[ 2 * k ] = chain[ end - 2 * k ];
				bone[ 2 * k + 1 ] = chain[ end - 2 * k + 1 ];

			}

		}

	}

	// The chain's ends duplicate the run's ends; keep its inner points.
	const inner = bone.length > 4 ? bone.subarray( 2, bone.length - 2 ) : new Float64Array( 0 );
	const outline = new Float64Array( run.length + inner.length );
	outline.set( run );
	outline.set( inner, run.length );
	return { outline, bone };

}
