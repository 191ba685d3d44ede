// Benchmark: the flat diagram's mid-sagittal section and the constriction, per articulation frame,
// on the real head in Node (the built meshes, the tongue rig with the collision tables, the face
// and velum rigs), for seeded random poses (every parameter uniform over its range). Measured in
// this run, over the same frames:
//   section    ours     DiagramSection.cut(): the tongue, velum and lips recut and chained in
//                       preallocated buffers (core/midSection.js), the mandible's cut posed;
//              naive    the same moving parts cut triangle by triangle into new arrays (the
//                       mandible's vertices posed first) and chained with a Map of point keys
//                       (core/sectionPolygon.js chainSegments), as a first version would;
//   constriction ours   core/constriction.js findConstriction (warm start, chunk boxes);
//              brute    every floor point against every roof segment and back, no pruning.
// The goal: the diagram's section under 0.3 ms median.
//
//   node bench/diagram.bench.mjs [samples]
import { existsSync } from 'node:fs';
import { dirname, join, resolve } from 'node:path';
import { fileURLToPath } from 'node:url';

import { chainSegments } from '../web/src/core/sectionPolygon.js';
import { DiagramSection } from '../web/src/scene/DiagramSection.js';
import { loadBuiltHead } from '../tests/js/support/builtHead.js';
import { median, random } from './support/stats.mjs';

const REPO = resolve( dirname( fileURLToPath( import.meta.url ) ), '..' );
const SAMPLES = Number( process.argv[ 2 ] ?? 30 );
const FRAMES = 40; // frames per sample, each with new parameters
const SEED = 1998;
const GOAL_MS = 0.3;

if ( ! existsSync( join( REPO, 'assets', 'build', 'manifest.json' ) ) ) {

	console.error( 'assets/build is missing: run `glasshead build` first' );
	process.exit( 1 );

}

const { head, articulation, landmarks } = await loadBuiltHead();
const diagram = new DiagramSection( head, { landmarks } );
const state = articulation.state;
const next = random( SEED );
const poses = Array.from( { length: SAMPLES * FRAMES }, () => state.minimum.map( ( lo, k ) => lo + ( state.maximum[ k ] - lo ) * next() ) );

/** The naive section: new arrays per frame, a Map to chain. Returns the chains per part. */
function naiveSection() {

	const out = [];
	for ( const mesh of diagram.meshes ) {

		if ( mesh.motion === 'still' ) continue;
		const source = mesh.scenePart.geometry.attributes.position.array;
		const pose = diagram.poseOf( mesh );
		const positions = pose ? posed( source, pose ) : source;
		const index = mesh.section.index;
		const segments = [];
		for ( let t = 0; t < index.length; t += 3 ) {

			const tri = [ index[ t ], index[ t + 1 ], index[ t + 2 ] ].map( ( v ) => [ positions[ 3 * v ], positions[ 3 * v + 1 ], positions[ 3 * v + 2 ] ] );
			const cut = [];
			for ( let e = 0; e < 3; e ++ ) {

				const a = tri[ e ], b = tri[ ( e + 1 ) % 3 ];
				if ( ( a[ 2 ] >= 0 ) === ( b[ 2 ] >= 0 ) ) continue;
				const s = a[ 2 ] / ( a[ 2 ] - b[ 2 ] );
				cut.push( a[ 0 ] + ( b[ 0 ] - a[ 0 ] ) * s, a[ 1 ] + ( b[ 1 ] - a[ 1 ] ) * s, 0 );

			}

			if ( cut.length === 6 ) segments.push( ...cut );

		}

		out.push( chainSegments( Float64Array.from( segments ), segments.length / 6 ) );

	}

	return out;

}

function posed( source, pose ) {

	const out = new Float32Array( source.length );
	for ( let v = 0; v < source.length; v += 3 ) {

		const x = source[ v ], y = source[ v + 1 ], z = source[ v + 2 ];
		out[ v ] = pose[ 0 ] * x + pose[ 1 ] * y + pose[ 2 ] * z + pose[ 3 ];
		out[ v + 1 ] = pose[ 4 ] * x + pose[ 5 ] * y + pose[ 6 ] * z + pose[ 7 ];
		out[ v + 2 ] = pose[ 8 ] * x + pose[ 9 ] * y + pose[ 10 ] * z + pose[ 11 ];

	}

	return out;

}

/** Every floor point against every roof segment and back: the least squared distance. */
function bruteConstriction() {

	let best = Infinity;
	const pass = ( from, to ) => {

		for ( const a of from ) for ( let k = 0; k < a.pointCount; k ++ ) {

			const x = a.points[ 2 * k ], y = a.points[ 2 * k + 1 ];
			for ( const b of to ) for ( let c = 0; c < b.chainCount; c ++ ) {

				const first = b.starts[ c ], n = b.starts[ c + 1 ] - first;
				for ( let s = 0; s < ( b.closed[ c ] ? n : n - 1 ); s ++ ) {

					const i = first + s, j = first + ( s + 1 ) % n;
					const ax = b.points[ 2 * i ], ay = b.points[ 2 * i + 1 ];
					const dx = b.points[ 2 * j ] - ax, dy = b.points[ 2 * j + 1 ] - ay;
					const l2 = dx * dx + dy * dy;
					const t = l2 > 0 ? Math.min( 1, Math.max( 0, ( ( x - ax ) * dx + ( y - ay ) * dy ) / l2 ) ) : 0;
					best = Math.min( best, ( ax + t * dx - x ) ** 2 + ( ay + t * dy - y ) ** 2 );

				}

			}

		}

	};
	pass( diagram.floor, diagram.roof );
	pass( diagram.roof, diagram.floor );
	return Math.sqrt( best );

}

const now = () => Number( process.hrtime.bigint() ) / 1e6;

/** Median over samples of the mean ms per frame of run(), each frame posed first (not timed). */
function time( run ) {

	const perSample = [];
	for ( let sample = 0; sample < SAMPLES; sample ++ ) {

		let total = 0;
		for ( let f = 0; f < FRAMES; f ++ ) {

			state.values.set( poses[ sample * FRAMES + f ] );
			state.touch();
			articulation.update();
			const start = now();
			run();
			total += now() - start;

		}

		perSample.push( total / FRAMES );

	}

	return median( perSample );

}

// The two constriction searches agree (the pruning is exact).
let worst = 0;
for ( let k = 0; k < 50; k ++ ) {

	state.values.set( poses[ k ] );
	state.touch();
	articulation.update();
	diagram.cut().findConstriction();
	worst = Math.max( worst, Math.abs( diagram.result[ 0 ] - bruteConstriction() ) );

}

for ( let warm = 0; warm < 3; warm ++ ) {

	time( () => diagram.cut() );
	time( naiveSection );
	time( () => diagram.findConstriction() );
	time( bruteConstriction );

}

const ours = time( () => diagram.cut() );
const naive = time( naiveSection );
const search = time( () => diagram.findConstriction() );
const brute = time( bruteConstriction );
const moving = diagram.meshes.filter( ( m ) => m.motion !== 'still' );
console.log( `diagram section: ${ moving.map( ( m ) => m.name ).join( ', ' ) } (${ moving.reduce( ( n, m ) => n + m.section.index.length / 3, 0 ) } triangles recut or posed per frame); ${ SAMPLES } samples x ${ FRAMES } frames, seed ${ SEED }` );
console.log( `  section       ours  ${ ours.toFixed( 4 ) } ms median   naive ${ naive.toFixed( 4 ) } ms   ratio ${ ( naive / ours ).toFixed( 1 ) }x   goal < ${ GOAL_MS } ms: ${ ours < GOAL_MS ? 'met' : 'NOT met' }` );
console.log( `  constriction  ours  ${ search.toFixed( 4 ) } ms median   brute ${ brute.toFixed( 4 ) } ms   ratio ${ ( brute / search ).toFixed( 1 ) }x   largest difference ${ worst.toExponential( 1 ) } mm` );
console.log( `  section + constriction ${ ( ours + search ).toFixed( 4 ) } ms median` );
