// Benchmark: the tongue against the velum and the pharyngeal wall, per frame in Node, on the real
// built head and seeded random poses (every tongue parameter and velum_opening uniform over its
// range; the tongue first corrected against the palate, as in the frame).
//
// Methods, timed in this run over the same poses, interleaved pose by pose:
//   ours  web/src/core/tractCollision.js: the depth screen, then exact two-sided Moller-Trumbore
//         over the triangles listed in the vertex's cell of directions (no refit, no search);
//   bvh   three-mesh-bvh: the velum's BVH refit to the posed velum each frame, then raycastFirst
//         from T to each vertex on it and on the wall's BVH, the nearer hit taken: the same
//         question, asked the usual way.
// Exactness of ours is judged against bvh for every vertex of every pose: no vertex may stay more
// than 0.1 mm beyond the first crossing, and no vertex that was outside may move.
//
//   node bench/tract_collision.bench.mjs [poses]      (GLASSHEAD_BENCH_QUICK=1: 30 poses, 1 round)
import { BufferAttribute, BufferGeometry, DoubleSide, Ray, Vector3 } from 'three';
import { MeshBVH } from 'three-mesh-bvh';

import { correctVertices } from '../web/src/core/collision.js';
import { COLLISION_TOL } from '../web/src/core/constants.js';
import { poseVelum, velumSegment } from '../web/src/core/velum.js';
import { correctTract, setTractPose } from '../web/src/core/tractCollision.js';
import { loadBuiltHead } from '../tests/js/support/builtHead.js';
import { check, count } from './support/quick.mjs';
import { median, random } from './support/stats.mjs';

const POSES = Number( process.argv[ 2 ] ?? count( 300, 30 ) );
const SEED = 1998;
const ROUNDS = count( 5, 1 );

const { head, articulation } = await loadBuiltHead();
const collider = articulation.tract;
const velum = articulation.velum;
if ( ! collider ) throw new Error( `the built head has no tract collider: ${ articulation.velumError ?? 'no pharynx mesh' }` );
const rig = articulation.rig;
const n = rig.vertexCount;
const state = articulation.state;

// Inputs: the tongue after the palate, and the posed velum, per pose.
const next = random( SEED );
const inputs = [];
const surface = rig.createSurface();
for ( let p = 0; p < POSES; p ++ ) {

	const values = state.minimum.map( ( lo, k ) => lo + ( state.maximum[ k ] - lo ) * next() );
	rig.evaluate( values, surface );
	const positions = surface.positions.slice();
	correctVertices( positions, n, articulation.tables, null, null );
	const opening = values[ velum.index ];
	const velumPositions = poseVelum( velum.rig, opening, new Float32Array( 3 * velum.rig.vertexCount ) );
	inputs.push( { positions, opening, first: velumSegment( velum.rig, opening ), share: velum.rig.share[ 0 ], velumPositions } );

}

const [ ox, oy, oz ] = collider.origin;
const work = new Float32Array( 3 * n );
const flags = new Uint8Array( n );
const stats = new Int32Array( 3 );

function ours( input ) {

	setTractPose( collider, 0, input.velumPositions, input.first, input.share );
	correctTract( work, n, collider, flags, stats );

}

// three-mesh-bvh on the same meshes: the velum's geometry shares one position array, refit per pose.
const velumGeometry = new BufferGeometry(); // three-mesh-bvh reorders its index: a copy
const velumArray = new Float32Array( 3 * velum.rig.vertexCount );
velumArray.set( velum.rig.rest );
velumGeometry.setAttribute( 'position', new BufferAttribute( velumArray, 3 ) );
velumGeometry.setIndex( new BufferAttribute( velum.triangles.slice(), 1 ) );
const velumBvh = new MeshBVH( velumGeometry );
const wall = head.part( 'pharynx' ).geometry;
const wallBvh = new MeshBVH( wall.clone() );
const ray = new Ray( new Vector3( ox, oy, oz ), new Vector3() );

function bvh( input ) {

	velumArray.set( input.velumPositions );
	velumBvh.refit();
	for ( let v = 0; v < n; v ++ ) {

		const px = work[ 3 * v ] - ox, py = work[ 3 * v + 1 ] - oy, pz = work[ 3 * v + 2 ] - oz;
		const r = Math.sqrt( px * px + py * py + pz * pz );
		if ( r === 0 ) continue;
		ray.direction.set( px / r, py / r, pz / r );
		const a = velumBvh.raycastFirst( ray, DoubleSide, 0, r );
		const b = wallBvh.raycastFirst( ray, DoubleSide, 0, r );
		const hit = a === null ? b : b === null || a.distance <= b.distance ? a : b;
		if ( hit !== null && hit.distance < r ) hit.point.toArray( work, 3 * v );

	}

}

// Per pose, the median over ROUNDS timed passes (one warm-up pass first), methods interleaved.
const methods = { ours, bvh };
const times = Object.fromEntries( Object.keys( methods ).map( ( name ) => [ name, inputs.map( () => [] ) ] ) );
for ( let round = 0; round <= ROUNDS; round ++ ) {

	inputs.forEach( ( input, p ) => {

		for ( const [ name, method ] of Object.entries( methods ) ) {

			work.set( input.positions );
			const start = performance.now();
			method( input );
			if ( round > 0 ) times[ name ][ p ].push( performance.now() - start );

		}

	} );

}

// Exactness: ours against the first crossing three-mesh-bvh finds for each vertex before correction.
let deepest = 0, innocent = 0, corrected = 0, missedInside = 0, tested = 0;
const budget = COLLISION_TOL.depth;
for ( const input of inputs ) {

	work.set( input.positions );
	ours( input );
	tested += stats[ 1 ];
	velumArray.set( input.velumPositions );
	velumBvh.refit();
	for ( let v = 0; v < n; v ++ ) {

		const x = input.positions[ 3 * v ] - ox, y = input.positions[ 3 * v + 1 ] - oy, z = input.positions[ 3 * v + 2 ] - oz;
		const r = Math.sqrt( x * x + y * y + z * z );
		ray.direction.set( x / r, y / r, z / r );
		const a = velumBvh.raycastFirst( ray, DoubleSide, 0, Infinity );
		const b = wallBvh.raycastFirst( ray, DoubleSide, 0, Infinity );
		const first = Math.min( a?.distance ?? Infinity, b?.distance ?? Infinity );
		const moved = work[ 3 * v ] !== input.positions[ 3 * v ] || work[ 3 * v + 1 ] !== input.positions[ 3 * v + 1 ] || work[ 3 * v + 2 ] !== input.positions[ 3 * v + 2 ];
		if ( moved ) corrected ++;
		if ( r > first + budget ) {

			const after = Math.hypot( work[ 3 * v ] - ox, work[ 3 * v + 1 ] - oy, work[ 3 * v + 2 ] - oz );
			deepest = Math.max( deepest, after - first );
			if ( ! moved ) missedInside ++;

		} else if ( r < first - budget && moved ) innocent ++;

	}

}

const perPose = Object.fromEntries( Object.entries( times ).map( ( [ name, list ] ) => [ name, list.map( median ) ] ) );
const ms = ( v ) => `${ v.toFixed( 4 ) } ms`;
console.log( `tongue against velum and pharyngeal wall: ${ n } tongue vertices, ${ velum.triangles.length / 3 } velum and ${ wall.index.count / 3 } wall triangles, ${ POSES } poses (seed ${ SEED }), ${ ROUNDS } rounds` );
console.log( `  ours (depth screen + cell lists)             median ${ ms( median( perPose.ours ) ) } per frame` );
console.log( `  three-mesh-bvh refit + raycastFirst          median ${ ms( median( perPose.bvh ) ) } per frame` );
console.log( `  ratio: ours faster by ${ ( median( perPose.bvh ) / median( perPose.ours ) ).toFixed( 1 ) }x` );
console.log( `  per frame: ${ ( tested / POSES ).toFixed( 0 ) } vertices tested, ${ ( corrected / POSES ).toFixed( 1 ) } corrected` );
console.log( `  exactness: deepest left ${ deepest.toExponential( 2 ) } mm beyond the first crossing (budget ${ budget } mm), ${ missedInside } inside vertices left, ${ innocent } outside vertices moved` );
const exact = deepest <= budget && missedInside === 0 && innocent === 0;
console.log( `tract collision: ${ exact ? 'exact' : 'NOT EXACT' }, ${ ms( median( perPose.ours ) ) } median` );
check( 'ours is exact against three-mesh-bvh', exact, `deepest ${ deepest.toExponential( 2 ) } mm, ${ missedInside } left inside, ${ innocent } moved wrongly` );
check( 'the poses reach the velum or the wall', corrected > 0, 'no vertex was corrected: nothing was checked' );
