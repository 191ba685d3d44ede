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
// Checked on the way: ours and naive cut the same points, and the two constriction searches
// find the same width. The goal: the diagram's section under 0.3 ms median.
//
//   node bench/diagram.bench.mjs [samples]      (GLASSHEAD_BENCH_QUICK=1: 3 samples x 10 frames)
import { WELD_MM } from '../web/src/core/sectionPolygon.js';
import { DiagramSection } from '../web/src/scene/DiagramSection.js';
import { loadBuiltHead } from '../tests/js/support/builtHead.js';
import { builtFile } from './support/assets.mjs';
import { bruteConstriction as bruteOf, naiveSection as naiveOf } from './support/naiveDiagram.mjs';
import { check, count } from './support/quick.mjs';
import { median, random } from './support/stats.mjs';

const SAMPLES = Number( process.argv[ 2 ] ?? count( 30, 3 ) );
const FRAMES = count( 40, 10 ); // frames per sample, each with new parameters
const SEED = 1998;
const GOAL_MS = 0.3;
const CHECKED = count( 50, 10 ); // poses on which ours is checked against the naive versions
/** mm: the naive chains weld points this close into one (core/sectionPolygon.js); ours keeps each. */
const SECTION_TOLERANCE_MM = WELD_MM;
const WIDTH_TOLERANCE_MM = 1e-9;

builtFile( 'manifest.json' ); // exits with a message when there is no build

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

/** The farthest any point of one point set (x y pairs) lies from the other set, both ways. */
function pointSetDistance( a, aCount, b, bCount ) {

	const oneWay = ( p, pCount, q, qCount ) => {

		let worst = 0;
		for ( let i = 0; i < pCount; i ++ ) {

			let best = Infinity;
			for ( let j = 0; j < qCount && best > 0; j ++ ) best = Math.min( best, Math.hypot( p[ 2 * i ] - q[ 2 * j ], p[ 2 * i + 1 ] - q[ 2 * j + 1 ] ) );
			worst = Math.max( worst, best );

		}

		return worst;

	};
	if ( ( aCount === 0 ) !== ( bCount === 0 ) ) return Infinity;
	return Math.max( oneWay( a, aCount, b, bCount ), oneWay( b, bCount, a, aCount ) );

}

// Ours against the naive versions, pose by pose: the same section points of every moving part,
// and the same constriction width (the pruning is exact).
let worst = 0, sectionGap = 0, sectionPoints = 0;
for ( let k = 0; k < Math.min( CHECKED, poses.length ); k ++ ) {

	state.values.set( poses[ k ] );
	state.touch();
	articulation.update();
	diagram.cut().findConstriction();
	worst = Math.max( worst, Math.abs( diagram.result[ 0 ] - bruteConstriction() ) );
	const chains = naiveSection();
	diagram.meshes.filter( ( m ) => m.motion !== 'still' ).forEach( ( mesh, m ) => {

		const naivePoints = Float64Array.from( chains[ m ].flatMap( ( chain ) => Array.from( chain.points ) ) );
		sectionGap = Math.max( sectionGap, pointSetDistance( mesh.section.points, mesh.section.pointCount, naivePoints, naivePoints.length / 2 ) );
		sectionPoints += mesh.section.pointCount;

	} );

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
check( 'ours and naive cut the same section', sectionPoints > 0 && sectionGap <= SECTION_TOLERANCE_MM, `${ sectionPoints } points, farthest ${ sectionGap.toExponential( 1 ) } mm apart (tolerance ${ SECTION_TOLERANCE_MM } mm)` );
check( 'the pruned constriction search finds the brute-force width', worst <= WIDTH_TOLERANCE_MM, `largest difference ${ worst.toExponential( 1 ) } mm` );
