// Benchmark: the tract's area function per pose in JavaScript (scene/TractAcoustics.js with
// core/areaFunction.js), on the real head in Node, for seeded random poses (every parameter
// uniform over its range). Each frame is posed and the diagram's section recut first (not timed;
// bench/diagram.bench.mjs times those). Measured in this run, over the same frames:
//   area function  ours   the moving parts' segments copied into buffers sized once, every
//                         station against every segment in typed arrays, no allocation;
//                  plain  the same method written plainly: each frame builds its parts as
//                         arrays of segment objects and measures each station with map and
//                         Math.min over them, as a first version would;
//   formants       the lossy tube's formants of that area function (core/tubeAcoustics.js).
// Checked on the way: ours and plain give the same widths. The goal: the area function
// under 1 ms median per pose.
//
//   node bench/area_function.bench.mjs [samples]   (GLASSHEAD_BENCH_QUICK=1: 3 samples x 10 frames)
import { DiagramSection } from '../web/src/scene/DiagramSection.js';
import { TractAcoustics } from '../web/src/scene/TractAcoustics.js';
import { TRACT_STATION_STEP_MM } from '../web/src/core/constants.js';
import { loadBuiltHead } from '../tests/js/support/builtHead.js';
import { builtFile } from './support/assets.mjs';
import { check, count } from './support/quick.mjs';
import { median, random } from './support/stats.mjs';

const SAMPLES = Number( process.argv[ 2 ] ?? count( 30, 3 ) );
const FRAMES = count( 20, 10 );
const SEED = 2031;
const GOAL_MS = 1;
const WIDTH_TOLERANCE_MM = 1e-9;

// builtFile exits with a message when there is no build.
const section = JSON.parse( builtFile( 'tract-section.json' ).toString( 'utf8' ) );
const { head, articulation, landmarks } = await loadBuiltHead();
const diagram = new DiagramSection( head, { landmarks } );
const tract = new TractAcoustics( diagram, section, articulation.state );
const state = articulation.state;
const next = random( SEED );
const poses = Array.from( { length: SAMPLES * FRAMES }, () => state.minimum.map( ( lo, k ) => lo + ( state.maximum[ k ] - lo ) * next() ) );
const now = () => Number( process.hrtime.bigint() ) / 1e6;

function setPose( k ) {

	state.values.set( poses[ k ] );
	state.touch();
	articulation.update();
	diagram.update();

}

// The plain version: parts as arrays of { a, b } segments built anew, each station measured with
// map and Math.min. The same rule (docs/acoustics.md), so the same widths.
function plainParts( views ) {

	return views.map( ( view ) => ( {
		solid: view.solid,
		segments: Array.from( { length: view.count }, ( _, k ) => ( { a: [ view.segments[ 4 * k ], view.segments[ 4 * k + 1 ] ], b: [ view.segments[ 4 * k + 2 ], view.segments[ 4 * k + 3 ] ] } ) ),
	} ) );

}

function plainNearest( parts, p ) {

	const all = parts.flatMap( ( part ) => part.segments.map( ( { a, b } ) => {

		const ab = [ b[ 0 ] - a[ 0 ], b[ 1 ] - a[ 1 ] ];
		const t = Math.min( 1, Math.max( 0, ( ( p[ 0 ] - a[ 0 ] ) * ab[ 0 ] + ( p[ 1 ] - a[ 1 ] ) * ab[ 1 ] ) / Math.max( ab[ 0 ] ** 2 + ab[ 1 ] ** 2, 1e-12 ) ) );
		const q = [ a[ 0 ] + t * ab[ 0 ], a[ 1 ] + t * ab[ 1 ] ];
		return { d: Math.hypot( p[ 0 ] - q[ 0 ], p[ 1 ] - q[ 1 ] ), q };

	} ) );
	const best = all.reduce( ( m, s ) => ( s.d < m.d ? s : m ), { d: Infinity, q: p } );
	return best;

}

function plainInside( parts, p ) {

	return parts.some( ( part ) => part.solid && part.segments.filter( ( { a, b } ) => ( a[ 1 ] > p[ 1 ] ) !== ( b[ 1 ] > p[ 1 ] ) && p[ 0 ] < a[ 0 ] + ( p[ 1 ] - a[ 1 ] ) * ( b[ 0 ] - a[ 0 ] ) / ( b[ 1 ] - a[ 1 ] || 1 ) ).length % 2 === 1 );

}

function plainWidths() {

	tract.updateAreaFunction(); // only for the views' refresh and the lips' front; recomputed below
	const floor = plainParts( tract.floor ), roof = plainParts( tract.roof );
	const n = tract.stations.length / 2;
	const last = [ tract.stations[ 2 * n - 2 ], tract.stations[ 2 * n - 1 ] ];
	const reach = tract.where.lipFrontX - last[ 0 ];
	const extra = reach > 0 ? Math.ceil( reach / TRACT_STATION_STEP_MM ) : 0;
	const walk = [ ...Array.from( { length: n }, ( _, i ) => [ tract.stations[ 2 * i ], tract.stations[ 2 * i + 1 ] ] ),
		...Array.from( { length: extra }, ( _, i ) => [ last[ 0 ] + reach * ( i + 1 ) / extra, last[ 1 ] ] ) ];
	return walk.map( ( p ) => {

		const f = plainNearest( floor, p ), r = plainNearest( roof, p );
		const inF = plainInside( floor, p ), inR = plainInside( roof, p );
		if ( ( inF && inR ) || ( inF && plainInside( floor, r.q ) ) || ( inR && plainInside( roof, f.q ) ) ) return 0;
		const w = inF ? r.d - f.d : ( inR ? f.d - r.d : f.d + r.d );
		return Number.isFinite( w ) ? Math.max( 0, w ) : 0;

	} );

}

/** Median over samples of the mean ms per frame of run(), each frame posed first (not timed). */
function time( run ) {

	const perSample = [];
	for ( let sample = 0; sample < SAMPLES; sample ++ ) {

		let total = 0;
		for ( let f = 0; f < FRAMES; f ++ ) {

			setPose( sample * FRAMES + f );
			const start = now();
			run();
			total += now() - start;

		}

		perSample.push( total / FRAMES );

	}

	return median( perSample );

}

let worst = 0, stations = 0;
for ( let k = 0; k < Math.min( poses.length, count( 100, 10 ) ); k ++ ) {

	setPose( k );
	tract.updateAreaFunction();
	const ours = tract.tube.stationWidths.slice( 0, tract.tube.count );
	const plain = plainWidths();
	stations += plain.length;
	if ( plain.length !== ours.length ) worst = Infinity;
	else plain.forEach( ( w, i ) => ( worst = Math.max( worst, Math.abs( w - ours[ i ] ) ) ) );

}

for ( let warm = 0; warm < 2; warm ++ ) {

	time( () => tract.updateAreaFunction() );
	time( plainWidths );
	time( () => tract.updateAreaFunction() && tract.updateFormants() );

}

const ours = time( () => tract.updateAreaFunction() );
const plain = time( plainWidths );
const formants = time( () => tract.updateAreaFunction() && tract.updateFormants() ) - ours;
const segments = tract.floor.reduce( ( n, p ) => n + p.count, 0 ) + tract.roof.reduce( ( n, p ) => n + p.count, 0 );
console.log( `area function: ${ tract.stations.length / 2 } midline stations and the lips', ${ segments } segments; ${ SAMPLES } samples x ${ FRAMES } frames, seed ${ SEED }` );
console.log( `  area function  ours  ${ ours.toFixed( 4 ) } ms median   plain ${ plain.toFixed( 4 ) } ms   ratio ${ ( plain / ours ).toFixed( 1 ) }x   goal < ${ GOAL_MS } ms: ${ ours < GOAL_MS ? 'met' : 'NOT met' }` );
console.log( `  formants       ${ formants.toFixed( 4 ) } ms median more (the lossy tube of ${ tract.tube.count } sections)` );
console.log( JSON.stringify( { benchmark: 'area_function', ours_median_ms: Number( ours.toPrecision( 3 ) ), plain_median_ms: Number( plain.toPrecision( 3 ) ), ratio: Number( ( plain / ours ).toFixed( 1 ) ), formants_median_ms: Number( formants.toPrecision( 3 ) ), goal_ms: GOAL_MS, goal_met: ours < GOAL_MS } ) );
check( 'ours and plain give the same width at every station', stations > 0 && worst <= WIDTH_TOLERANCE_MM, `${ stations } stations, largest difference ${ worst } mm` );
