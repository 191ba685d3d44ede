// Benchmark: the whole per-frame CPU pipeline in Node on the real built head (assets/build: every
// scene mesh, the tongue rig with the collision tables, the face rig, the velum rig, the EPG
// layout and the landmarks), for seeded random poses (every parameter, velum_opening included,
// uniform over its range, so the velum is reposed every frame). One frame is what the workbench
// runs: Articulation.update() (tongue surface, collision correction, normals, jaw, face rig,
// velum pose and nasal port area, the EPG contacts and indices in its hook) and then
// DiagramSection.update() (the mid-sagittal section and the constriction), with the tongue
// corrected against the velum and the pharyngeal wall in between (core/tractCollision.js).
//
// Measured in this run, over the same poses, interleaved sample by sample so that the machine's
// load falls on all of them alike:
//   frame      the real frame, as above;
//   previous   the same Articulation and EPG hook without the velum, its collision and the
//              diagram: the pipeline before the tract's stages, so frame - previous is what they
//              cost;
//   naive      the real articulation frame followed by the diagram written the straightforward
//              way (bench/support/naiveDiagram.mjs: new arrays per triangle, a Map to chain, every
//              floor point against every roof segment), the peer the diagram's kernels replace.
// Each stage is then timed on its own, rerun on the inputs of the frame just computed (the velum
// told its opening changed), so that a stage over budget can be named, and the naive section
// beside them as the section's own baseline.
// Checked on the way: the frame's EPG contacts and constriction are those of the brute-force
// references (every probe against every triangle; every floor point against every roof segment).
// The goals: the whole frame under 1 ms median, the diagram's section under 0.3 ms.
//
//   node bench/frame.bench.mjs [samples]      (GLASSHEAD_BENCH_QUICK=1: 3 samples x 10 frames)
import { correctVertices, STAT_CORRECTED } from '../web/src/core/collision.js';
import { electrodeContactsBruteForce } from '../web/src/core/epgContacts.js';
import { jawPose } from '../web/src/core/jaw.js';
import { vertexNormals } from '../web/src/core/meshVolume.js';
import { nasalPortArea, velumSegment } from '../web/src/core/velum.js';
import { correctTract, setTractPose } from '../web/src/core/tractCollision.js';
import { DiagramSection } from '../web/src/scene/DiagramSection.js';
import { createEpgLive } from '../web/src/scene/EpgLive.js';
import { loadBuiltHead } from '../tests/js/support/builtHead.js';
import { builtFile, builtJson } from './support/assets.mjs';
import { bruteConstriction, naiveSection } from './support/naiveDiagram.mjs';
import { check, count } from './support/quick.mjs';
import { median, random } from './support/stats.mjs';

const SAMPLES = Number( process.argv[ 2 ] ?? count( 40, 3 ) );
const FRAMES = count( 40, 10 ); // frames per sample, each with new parameters
const WARM_ROUNDS = count( 3, 1 );
const SEED = 1998;
const FRAME_GOAL_MS = 1;
const SECTION_GOAL_MS = 0.3;

// Each exits with a message when missing.
for ( const name of [ 'manifest.json', 'tongue-rig.json', 'collision-tables.bin', 'face-rig.json', 'velum-rig.json', 'epg-layout.json', 'landmarks.json' ] ) builtFile( name );

const { head, articulation, landmarks } = await loadBuiltHead();
const velum = articulation.velum;
const faceRig = articulation.faceRig;
const tract = articulation.tract;
if ( ! tract ) throw new Error( 'the built head has no tract collider (no pharynx mesh?)' );
if ( ! velum || ! faceRig ) throw new Error( `the built head has no ${ velum ? 'face' : 'velum' } rig: ${ articulation.velumError ?? articulation.faceRigError }` );
const layout = builtJson( 'epg-layout.json' );
const epg = createEpgLive( { layout, tongueTriangles: articulation.triangles, vertexCount: articulation.vertexCount } );
articulation.onCorrected( ( positions ) => epg.update( positions ) );
const diagram = new DiagramSection( head, { landmarks } );

const state = articulation.state;
const values = state.values;
const next = random( SEED );
const poses = Array.from( { length: SAMPLES * FRAMES }, () => state.minimum.map( ( lo, k ) => lo + ( state.maximum[ k ] - lo ) * next() ) );

function setPose( k ) {

	values.set( poses[ k ] );
	state.touch();

}

const variants = {
	frame( k ) {

		setPose( k );
		articulation.update();
		diagram.update();

	},
	previous( k ) {

		setPose( k );
		articulation.velum = null;
		articulation.tract = null;
		articulation.update();
		articulation.velum = velum;
		articulation.tract = tract;

	},
	naive( k ) {

		setPose( k );
		articulation.update();
		naiveSection( diagram );
		bruteConstriction( diagram );

	},
};

// The stages of one frame, each rerun alone on the frame's own inputs (as Articulation.update and
// DiagramSection.update call them).
const rig = articulation.rig;
const stages = {
	'tongue surface': () => rig.evaluate( values, articulation.surface, false ),
	'collision correction': () => {

		articulation.positions.set( articulation.surface.positions );
		correctVertices( articulation.positions, articulation.vertexCount, articulation.tables, articulation.flags, articulation.stats );

	},
	'tongue normals': () => vertexNormals( articulation.positions, articulation.triangles, articulation.normalSums, articulation.normals ),
	'jaw pose': () => jawPose( values[ articulation.jawIndex ], rig.jaw, articulation.jawPose ),
	'face rig': () => {

		faceRig.last.fill( NaN ); // the pose returns at once when nothing changed
		faceRig.pose( values, articulation.jawPose );

	},
	'velum pose': () => {

		velum.opening = NaN;
		velum.pose( values );

	},
	'  of which nasal port area': () => nasalPortArea( velum.rig, values[ velum.index ] ),
	'collision, velum and pharynx': () => {

		articulation.positions.set( articulation.surface.positions );
		correctVertices( articulation.positions, articulation.vertexCount, articulation.tables, null, null );
		setTractPose( tract, 0, velum.positions, velumSegment( velum.rig, values[ velum.index ] ), velum.rig.share[ 0 ] );
		correctTract( articulation.positions, articulation.vertexCount, tract, articulation.tractFlags, articulation.tractStats );

	},
	'  of which the palate again': () => {

		articulation.positions.set( articulation.surface.positions );
		correctVertices( articulation.positions, articulation.vertexCount, articulation.tables, null, null );

	},
	'EPG contacts and indices': () => epg.update( articulation.positions ),
	'diagram section': () => diagram.cut(),
	'constriction': () => diagram.findConstriction(),
	'  baseline: naive section': () => naiveSection( diagram ),
};

/** Per variant: median over samples of the mean ms per frame; variants interleaved per sample. */
function timeVariants( samples ) {

	const perSample = Object.fromEntries( Object.keys( variants ).map( ( name ) => [ name, [] ] ) );
	for ( let s = 0; s < samples; s ++ ) {

		for ( const [ name, run ] of Object.entries( variants ) ) {

			const start = performance.now();
			for ( let f = 0; f < FRAMES; f ++ ) run( s * FRAMES + f );
			perSample[ name ].push( ( performance.now() - start ) / FRAMES );

		}

	}

	return Object.fromEntries( Object.entries( perSample ).map( ( [ name, list ] ) => [ name, median( list ) ] ) );

}

/** Per stage: median over samples of the mean ms per frame, each frame computed first (untimed). */
function timeStages( samples ) {

	const names = Object.keys( stages );
	const perSample = names.map( () => [] );
	const totals = new Float64Array( names.length );
	for ( let s = 0; s < samples; s ++ ) {

		totals.fill( 0 );
		for ( let f = 0; f < FRAMES; f ++ ) {

			variants.frame( s * FRAMES + f );
			names.forEach( ( name, k ) => {

				const start = performance.now();
				stages[ name ]();
				totals[ k ] += performance.now() - start;

			} );

		}

		names.forEach( ( _, k ) => perSample[ k ].push( totals[ k ] / FRAMES ) );

	}

	return Object.fromEntries( names.map( ( name, k ) => [ name, median( perSample[ k ] ) ] ) );

}

for ( let warm = 0; warm < WARM_ROUNDS; warm ++ ) {

	timeVariants( Math.min( 4, SAMPLES ) );
	timeStages( Math.min( 4, SAMPLES ) );

}

const whole = timeVariants( SAMPLES );
const stage = timeStages( SAMPLES );

// Every pose once more, each frame's results against the brute-force references.
let touching = 0, contactMismatch = 0, contacted = 0, widthGap = 0;
const bruteFrame = new Uint8Array( epg.frame.length );
for ( let k = 0; k < poses.length; k ++ ) {

	variants.frame( k );
	touching += articulation.stats[ STAT_CORRECTED ] > 0 ? 1 : 0;
	electrodeContactsBruteForce( epg.model, articulation.positions, bruteFrame );
	contacted += epg.contacted;
	for ( let c = 0; c < bruteFrame.length; c ++ ) contactMismatch += bruteFrame[ c ] !== epg.frame[ c ] ? 1 : 0;
	diagram.findConstriction();
	widthGap = Math.max( widthGap, Math.abs( diagram.result[ 0 ] - bruteConstriction( diagram ) ) );

}

const ms = ( value ) => `${ value.toFixed( 4 ) } ms`;
const verdict = ( value, goal ) => ( value < goal ? 'met' : 'missed' );
const moving = diagram.meshes.filter( ( m ) => m.motion !== 'still' );
console.log( `per-frame pipeline on the built head: ${ articulation.vertexCount } tongue vertices, ${ velum.rig.vertexCount } velum vertices, ${ moving.reduce( ( n, m ) => n + m.section.index.length / 3, 0 ) } diagram triangles recut or posed; ${ SAMPLES } samples x ${ FRAMES } frames (seed ${ SEED }), ${ touching } of ${ poses.length } poses touching the palate` );
console.log( '  stage (rerun alone)            median' );
let sum = 0;
for ( const [ name, value ] of Object.entries( stage ) ) {

	if ( ! name.startsWith( ' ' ) ) sum += value;
	// The tract stage reruns the palate correction to have its input back; counted once.
	if ( name === '  of which the palate again' ) sum -= value;
	console.log( `  ${ name.padEnd( 30 ) } ${ ms( value ) }` );

}

console.log( `  ${ 'sum of stages'.padEnd( 30 ) } ${ ms( sum ) }` );
console.log( `  whole frame     ${ ms( whole.frame ) } median` );
console.log( `  previous        ${ ms( whole.previous ) } median (no velum, no diagram): the new stages add ${ ms( whole.frame - whole.previous ) }, ratio ${ ( whole.frame / whole.previous ).toFixed( 2 ) }x` );
console.log( `  naive diagram   ${ ms( whole.naive ) } median (allocating section, brute constriction): ours faster by ${ ( whole.naive / whole.frame ).toFixed( 1 ) }x` );
console.log( `whole frame: ${ whole.frame.toFixed( 3 ) } ms median (goal < ${ FRAME_GOAL_MS } ms): ${ verdict( whole.frame, FRAME_GOAL_MS ) }` );
const section = stage[ 'diagram section' ];
const naive = stage[ '  baseline: naive section' ];
console.log( `diagram section: ${ section.toFixed( 3 ) } ms (goal < ${ SECTION_GOAL_MS } ms): ${ verdict( section, SECTION_GOAL_MS ) }   (naive ${ naive.toFixed( 3 ) } ms, ratio ${ ( naive / section ).toFixed( 1 ) }x; with the constriction ${ ( section + stage.constriction ).toFixed( 3 ) } ms)` );
check( 'the frame\'s EPG contacts are the brute-force ones', contactMismatch === 0 && contacted > 0, `${ contactMismatch } cells differ over ${ poses.length } frames, ${ contacted } contacts` );
check( 'the frame\'s constriction is the brute-force width', widthGap <= 1e-9, `largest difference ${ widthGap.toExponential( 1 ) } mm` );
