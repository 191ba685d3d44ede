// The real-time tongue evaluator against the shared vectors written by the Python reference
// (tests/vectors/tongue-surface.json, tongue-jaw.json), plus its own guarantees: a closed,
// outward-wound mesh of fixed topology, and no allocation per evaluation.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { fewestGarbageCollections, garbageCollections } from './support/garbage.js';

import { TongueRig } from '../../web/src/core/tongue.js';
import { surfaceTriangles } from '../../web/src/core/tongueSurface.js';
import { meshVolume } from '../../web/src/core/meshVolume.js';
import { applyJawPose, jawPose, POSE_LENGTH } from '../../web/src/core/jaw.js';
import {
	TONGUE_VERTEX_TOLERANCE_MM, TONGUE_VOLUME_RELATIVE_TOLERANCE,
} from '../../web/src/core/constants.js';

import { near, readVectors, tolerance } from './support/vectors.js';

const SURFACES = readVectors( 'tongue-surface.json' );
const JAW = readVectors( 'tongue-jaw.json' );
const rig = new TongueRig( SURFACES.fixtures.rig );

test( 'the surface vectors hold 200 or more seeded random sets with unique descriptions', () => {

	const random = SURFACES.cases.filter( ( c ) => c.description.startsWith( 'random set' ) );
	assert.ok( random.length >= 200, `${random.length} random sets` );
	assert.ok( random.every( ( c ) => c.description.includes( `seed ${SURFACES.constants.seed}` ) ) );
	const descriptions = SURFACES.cases.map( ( c ) => c.description );
	assert.equal( new Set( descriptions ).size, descriptions.length );
	assert.equal( tolerance( SURFACES, 'vertex_mm' ), TONGUE_VERTEX_TOLERANCE_MM );
	assert.equal( tolerance( SURFACES, 'volume_relative' ), TONGUE_VOLUME_RELATIVE_TOLERANCE );

} );

test( 'the rig has 2,000 or more vertices, 9 or more sagittal and 3 x 7 coronal parameters', () => {

	assert.ok( rig.vertexCount >= 2000 );
	const groups = rig.parameters.map( ( p ) => p.group );
	assert.ok( groups.filter( ( g ) => g === 'tongue sagittal' ).length >= 9 );
	for ( const section of [ 'front', 'middle', 'back' ] ) {

		assert.equal( groups.filter( ( g ) => g === `tongue coronal ${section}` ).length, 7 );

	}

	for ( const p of rig.parameters ) {

		assert.ok( [ 'mm', 'deg', 'ratio' ].includes( p.unit ), p.name );
		assert.ok( p.min <= p.neutral && p.neutral <= p.max && p.min < p.max, p.name );

	}

} );

test( 'every vector set gives the Python probe positions, volume, centroid and bounds', () => {

	const surface = rig.createSurface();
	const values = new Float64Array( rig.parameterCount );
	const probes = SURFACES.fixtures.probe_vertices;
	const vertexMm = tolerance( SURFACES, 'vertex_mm' );
	const volumeRelative = tolerance( SURFACES, 'volume_relative' );
	let worst = 0;
	for ( const vector of SURFACES.cases ) {

		rig.evaluate( rig.valuesFrom( vector.input.params, values ), surface );
		const { positions } = surface;
		const expected = vector.expected;
		assert.equal( rig.vertexCount, expected.vertex_count );
		assert.equal( rig.triangleCount, expected.triangle_count );
		probes.forEach( ( v, k ) => {

			for ( let axis = 0; axis < 3; axis ++ ) {

				const error = Math.abs( positions[ 3 * v + axis ] - expected.probe_positions[ k ][ axis ] );
				worst = Math.max( worst, error );
				assert.ok( error <= vertexMm, `${vector.description}: vertex ${v} axis ${axis} off by ${error} mm` );

			}

		} );
		const volume = meshVolume( positions, surface.index );
		near( volume, expected.volume_mm3, volumeRelative * expected.volume_mm3, `${vector.description}: volume` );
		for ( let axis = 0; axis < 3; axis ++ ) {

			let sum = 0;
			let low = Infinity;
			let high = - Infinity;
			for ( let v = 0; v < rig.vertexCount; v ++ ) {

				const x = positions[ 3 * v + axis ];
				sum += x;
				low = Math.min( low, x );
				high = Math.max( high, x );

			}

			near( sum / rig.vertexCount, expected.centroid[ axis ], vertexMm, `${vector.description}: centroid` );
			near( low, expected.bounds_min[ axis ], vertexMm, `${vector.description}: bounds min` );
			near( high, expected.bounds_max[ axis ], vertexMm, `${vector.description}: bounds max` );

		}

	}

	// float32 positions: the worst difference is rounding, far inside the stated tolerance.
	assert.ok( worst < 1e-4, `largest probe difference ${worst} mm` );

} );

test( 'the surface is closed: every edge is shared by exactly two triangles, wound oppositely', () => {

	const index = rig.index;
	const edges = new Map();
	for ( let t = 0; t < index.length; t += 3 ) {

		for ( let k = 0; k < 3; k ++ ) {

			const key = `${index[ t + k ]}>${index[ t + ( k + 1 ) % 3 ]}`;
			assert.ok( ! edges.has( key ), `directed edge ${key} appears twice` );
			edges.set( key, true );

		}

	}

	for ( const key of edges.keys() ) {

		const [ a, b ] = key.split( '>' );
		assert.ok( edges.has( `${b}>${a}` ), `edge ${key} has no twin` );

	}

	assert.equal( rig.vertexCount - edges.size / 2 + index.length / 3, 2, 'Euler characteristic of a sphere' );

} );

test( 'normals are unit length and point away from the hub', () => {

	const surface = rig.evaluate( rig.valuesFrom( { jaw_opening: 10, tip_height: 6 } ), rig.createSurface() );
	const { positions, normals } = surface;
	let outward = 0;
	for ( let v = 0; v < rig.vertexCount; v ++ ) {

		const length = Math.hypot( normals[ 3 * v ], normals[ 3 * v + 1 ], normals[ 3 * v + 2 ] );
		near( length, 1, 1e-6, `normal ${v} length` );
		const dot = ( positions[ 3 * v ] - rig.hub[ 0 ] ) * normals[ 3 * v ] + ( positions[ 3 * v + 1 ] - rig.hub[ 1 ] ) * normals[ 3 * v + 1 ]
			+ positions[ 3 * v + 2 ] * normals[ 3 * v + 2 ];
		if ( dot > 0 ) outward ++;

	}

	assert.equal( outward, rig.vertexCount );
	assert.ok( meshVolume( positions, surface.index ) > 0 );

} );

test( 'evaluation writes into the same arrays and keeps the topology', () => {

	const surface = rig.createSurface();
	const { positions, normals, index } = surface;
	const copy = Uint32Array.from( index );
	rig.evaluate( rig.valuesFrom( { tip_advancement: 5 } ), surface );
	const tip = positions.slice();
	assert.equal( rig.evaluate( rig.valuesFrom( {} ), surface ), surface );
	assert.equal( surface.positions, positions );
	assert.equal( surface.normals, normals );
	assert.deepEqual( index, copy );
	assert.deepEqual( surfaceTriangles( rig.stationCount, rig.pageCount ), copy );
	assert.ok( positions.some( ( x, k ) => x !== tip[ k ] ), 'the second evaluation changed the positions' );

} );

test( 'evaluation without normals writes the same positions and leaves the normals alone', () => {

	const full = rig.evaluate( rig.valuesFrom( { tip_advancement: 5 } ), rig.createSurface() );
	const surface = rig.createSurface();
	surface.normals.fill( 7 );
	rig.evaluate( rig.valuesFrom( { tip_advancement: 5 } ), surface, false );
	assert.deepEqual( surface.positions, full.positions );
	assert.ok( surface.normals.every( ( x ) => x === 7 ) );

} );

test( 'evaluation allocates nothing: thousands of calls trigger no garbage collection', async () => {

	const surface = rig.createSurface();
	const values = rig.valuesFrom( { jaw_opening: 8, front_groove_depth: 3 } );
	for ( let k = 0; k < 200; k ++ ) rig.evaluate( values, surface ); // let the JIT settle
	const calls = 10000;
	const quiet = await fewestGarbageCollections( () => {

		for ( let k = 0; k < calls; k ++ ) {

			values[ 0 ] = ( k % 10 ) * 0.5;
			rig.evaluate( values, surface );

		}

	} );
	// The same loop with a fresh output per call shows that the probe does see allocation.
	const noisy = await garbageCollections( () => {

		for ( let k = 0; k < calls; k ++ ) rig.evaluate( values, rig.createSurface() );

	} );
	assert.equal( quiet, 0, `${quiet} collections during ${calls} evaluations` );
	assert.ok( noisy > 0, 'allocating a surface per call should trigger collections' );

} );

test( 'bad parameters are refused with the name and the range', () => {

	assert.throws( () => rig.valuesFrom( { tip_heigth: 1 } ), /unknown parameter 'tip_heigth'; known: tip_advancement, tip_height/ );
	const tip = rig.parameters[ rig.parameterIndex.get( 'tip_height' ) ];
	assert.throws( () => rig.valuesFrom( { tip_height: 40 } ), new RegExp( `tip_height = 40 is outside its range \\[${tip.min}, ${tip.max}\\] mm` ) );
	assert.throws( () => rig.valuesFrom( { jaw_opening: Number.NaN } ), /jaw_opening = NaN is not a finite number/ );

} );

test( 'the tip pair moves forward with tip advancement and the rest of the tongue stays', () => {

	const rest = rig.evaluate( rig.valuesFrom( {} ), rig.createSurface() ).positions;
	const moved = rig.evaluate( rig.valuesFrom( { tip_advancement: 6 } ), rig.createSurface() ).positions;
	let front = - Infinity;
	let frontMoved = - Infinity;
	let back = Infinity;
	let backMoved = Infinity;
	for ( let v = 0; v < rig.vertexCount; v ++ ) {

		front = Math.max( front, rest[ 3 * v ] );
		frontMoved = Math.max( frontMoved, moved[ 3 * v ] );
		back = Math.min( back, rest[ 3 * v ] );
		backMoved = Math.min( backMoved, moved[ 3 * v ] );

	}

	assert.ok( frontMoved - front > 4, `tip moved ${frontMoved - front} mm` );
	near( backMoved, back, 1e-4, 'root' );

} );

test( 'a radial move draws points in along their own rays, after the straight moves carried them off their rest rays', () => {

	// The dorsum forward and the blade back carry D..G off their rest rays; the lowering keeps
	// each point's direction from the hub and takes it 6 mm times its weight nearer.
	const names = SURFACES.fixtures.rig.sagittal.control_points.map( ( p ) => p.name );
	const weights = { D: 0.5, E: 1.0, F: 0.8, G: 0.3 };
	const straight = { dorsum_advancement: 6, blade_advancement: - 4, tip_height: 8 };
	const polar = ( values ) => {

		rig.posedControls( values );
		return names.map( ( _, i ) => {

			const x = rig.points[ 2 * i ] - rig.hub[ 0 ];
			const y = rig.points[ 2 * i + 1 ] - rig.hub[ 1 ];
			return [ Math.atan2( y, x ), Math.hypot( x, y ) ];

		} );

	};

	const before = polar( rig.valuesFrom( straight ) );
	const after = polar( rig.valuesFrom( { ...straight, dorsum_front_lowering: 6 } ) );
	names.forEach( ( name, i ) => {

		near( after[ i ][ 0 ], before[ i ][ 0 ], 1e-12, `${name} direction` );
		near( before[ i ][ 1 ] - after[ i ][ 1 ], 6 * ( weights[ name ] ?? 0 ), 1e-9, `${name} drawn in` );

	} );

} );

test( 'jaw poses and posed points match Python', () => {

	const pose = new Float64Array( POSE_LENGTH );
	const rotation = tolerance( JAW, 'rotation' ), translationMm = tolerance( JAW, 'translation_mm' );
	const pointMm = tolerance( JAW, 'point_mm' );
	for ( const vector of JAW.cases ) {

		jawPose( vector.input.opening_deg, JAW.fixtures.jaw, pose );
		// Row-major 3 x 4: entries 3, 7 and 11 are the translation (mm), the others rotation.
		vector.expected.pose.forEach( ( e, k ) => near( pose[ k ], e, k % 4 === 3 ? translationMm : rotation, `${vector.description}: pose ${k}` ) );
		const points = Float64Array.from( vector.input.points.flat() );
		const count = vector.input.points.length;
		applyJawPose( pose, points, count, 3, vector.input.weights, points );
		vector.expected.points.flat().forEach( ( e, k ) => near( points[ k ], e, pointMm, `${vector.description}: point ${k}` ) );

	}

} );

test( 'opening the jaw moves the chin end down and the tongue with it', () => {

	const pose = jawPose( 20, JAW.fixtures.jaw, new Float64Array( POSE_LENGTH ) );
	const chin = applyJawPose( pose, Float64Array.from( [ 25, - 30 ] ), 1, 2, null, new Float64Array( 2 ) );
	assert.ok( chin[ 1 ] < - 40, `chin y ${chin[ 1 ]}` );
	const closed = rig.evaluate( rig.valuesFrom( {} ), rig.createSurface() ).positions;
	const open = rig.evaluate( rig.valuesFrom( { jaw_opening: 10 } ), rig.createSurface() ).positions;
	let lowest = Infinity;
	let lowestOpen = Infinity;
	for ( let v = 0; v < rig.vertexCount; v ++ ) {

		lowest = Math.min( lowest, closed[ 3 * v + 1 ] );
		lowestOpen = Math.min( lowestOpen, open[ 3 * v + 1 ] );

	}

	assert.ok( lowestOpen < lowest - 5, `floor went from ${lowest} to ${lowestOpen}` );

} );
