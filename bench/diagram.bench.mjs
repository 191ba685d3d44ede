// Benchmark: the flat diagram's mid-sagittal section and the constriction, per articulation frame,
// on the real head in Node (the built meshes, the tongue rig with the collision tables, the face
// and velum rigs), for seeded random poses (every parameter uniform over its range). Measured in
// this run, over the same frames:
//   section    ours     DiagramSection.cut(): the tongue, velum and lips recut and chained in
//                       preallocated buffers (core/midSection.js), the mandible's cut posed;
//              naive    the same moving parts cut triangle by triangle into new arrays (the
//                       mandible's vertices posed first) and chained with a Map of point keys
//                       (core/sectionPolygon.js chainSegments), as a first version would
//                       (bench/support/naiveDiagram.mjs, shared with frame.bench.mjs);
//   constriction ours   core/constriction.js findConstriction (warm start, chunk boxes);
//              brute    every floor point against every roof segment and back, no pruning.
// The goal: the diagram's section under 0.3 ms median.
//
//   node bench/diagram.bench.mjs [samples]
import { existsSync } from 'node:fs';
import { dirname, join, resolve } from 'node:path';
import { fileURLToPath } from 'node:url';

import { DiagramSection } from '../web/src/scene/DiagramSection.js';
import { loadBuiltHead } from '../tests/js/support/builtHead.js';
import { bruteConstriction as bruteOf, naiveSection as naiveOf } from './support/naiveDiagram.mjs';
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
const naiveSection = () => naiveOf( diagram );
const bruteConstriction = () => bruteOf( diagram );
const poses = Array.from( { length: SAMPLES * FRAMES }, () => state.minimum.map( ( lo, k ) => lo + ( state.maximum[ k ] - lo ) * next() ) );

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
