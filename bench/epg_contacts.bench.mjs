// Benchmark: synthetic EPG per frame in JavaScript, contact plus indices (web/src/core/epgContacts.js
// and epgIndices.js), on corrected tongues of seeded poses: the 140 poses of the shared contact
// vectors (40 over every range, jaw included, and 100 with the tongue raised to the palate), each
// evaluated by the rig and corrected against the palate before timing starts. Prints the median
// time per frame of the kernel, over all frames and over the frames with contact, and of a naive
// baseline measured in the same run (every probe against every triangle), and their ratio.
// Checked: the kernel's frames are the baseline's, on every tongue and both grids.
// Goal: kernel median under 0.05 ms per frame.
//
//   node bench/epg_contacts.bench.mjs              the built assets (assets/build), else the vectors'
//   node bench/epg_contacts.bench.mjs --vectors    the vectors' own palate, tables and rig
//   GLASSHEAD_BENCH_QUICK=1                         11 runs of each instead of 201
import { existsSync, readFileSync } from 'node:fs';
import { dirname, join, resolve } from 'node:path';
import { fileURLToPath } from 'node:url';
import { performance } from 'node:perf_hooks';

import { correctVertices } from '../web/src/core/collision.js';
import { createContactModel, electrodeContacts, electrodeContactsBruteForce } from '../web/src/core/epgContacts.js';
import { epgIndices, INDEX_STRIDE } from '../web/src/core/epgIndices.js';
import { decodeCollisionTables } from '../web/src/core/tables.js';
import { TongueRig } from '../web/src/core/tongue.js';
import { check, count } from './support/quick.mjs';
import { median } from './support/stats.mjs';

const HERE = dirname( fileURLToPath( import.meta.url ) );
const REPO = resolve( HERE, '..' );
const ASSETS = process.env.GLASSHEAD_ASSETS_DIR ?? join( REPO, 'assets', 'build' );
const VECTORS = JSON.parse( readFileSync( join( REPO, 'tests', 'vectors', 'epg-contacts.json' ), 'utf8' ) );
const FIXTURES = VECTORS.fixtures;
const RUNS = count( 201, 11 );
const WARMUP = count( 30, 3 );
const BASELINE_RUNS = count( 5, 1 );
const GOAL_MS = 0.05;

const read = ( path ) => readFileSync( path );
const builtFiles = [ 'tongue-rig.json', 'collision-tables.bin', 'epg-layout.json' ].map( ( name ) => join( ASSETS, name ) );
const useBuilt = ! process.argv.includes( '--vectors' ) && builtFiles.every( existsSync );
const rigDefinition = useBuilt ? JSON.parse( read( builtFiles[ 0 ] ) ) : FIXTURES.rig;
const tablesBytes = useBuilt ? read( builtFiles[ 1 ] ) : read( join( REPO, 'tests', 'vectors', FIXTURES.tables.file ) );
const layout = useBuilt ? JSON.parse( read( builtFiles[ 2 ] ) ) : FIXTURES.layout;
const source = useBuilt ? `built assets in ${ ASSETS }` : `the contact vectors' palate (${ FIXTURES.tables.maxilla_triangles } triangles)`;

const rig = new TongueRig( rigDefinition );
const tables = decodeCollisionTables( tablesBytes );
const poses = [ {}, ...VECTORS.cases.filter( ( c ) => 'params' in c.input ).map( ( c ) => c.input.params ) ];
const surface = rig.createSurface();
const tongues = poses.map( ( params ) => {

	rig.evaluate( rig.valuesFrom( params ), surface );
	const positions = Float32Array.from( surface.positions );
	correctVertices( positions, rig.vertexCount, tables, null, null );
	return positions;

} );

const models = Object.fromEntries( [ 'reading62', 'dense96' ].map( ( g ) => [ g, createContactModel( layout.grids[ g ], rig.index, rig.vertexCount ) ] ) );
const frame = new Uint8Array( 96 );
const indices = new Float64Array( INDEX_STRIDE );
let sink = 0;

/** Median over runs of the mean time per frame of one pass over `set`. */
function perFrameMedian( set, frameFn, runs = RUNS, warmup = WARMUP ) {

	for ( let k = 0; k < warmup; k ++ ) for ( const positions of set ) frameFn( positions );
	const times = [];
	for ( let k = 0; k < runs; k ++ ) {

		const t0 = performance.now();
		for ( const positions of set ) frameFn( positions );
		times.push( ( performance.now() - t0 ) / set.length );

	}

	return median( times );

}

const kernel = ( model ) => ( positions ) => {

	sink += electrodeContacts( model, positions, frame );
	epgIndices( frame, 0, indices );
	sink += indices[ 1 ];

};
const naive = ( model ) => ( positions ) => {

	sink += electrodeContactsBruteForce( model, positions, frame );
	epgIndices( frame, 0, indices );
	sink += indices[ 1 ];

};

// The kernel against the baseline, frame by frame, before any timing.
const bruteFrame = new Uint8Array( 96 );
let cellsDiffer = 0, contacts = 0;
for ( const model of Object.values( models ) ) for ( const positions of tongues ) {

	contacts += electrodeContacts( model, positions, frame );
	electrodeContactsBruteForce( model, positions, bruteFrame );
	for ( let c = 0; c < model.cells; c ++ ) cellsDiffer += frame[ c ] !== bruteFrame[ c ] ? 1 : 0;

}

const withContact = tongues.filter( ( positions ) => electrodeContacts( models.reading62, positions, frame ) > 0 );
const readingMs = perFrameMedian( tongues, kernel( models.reading62 ) );
const contactMs = perFrameMedian( withContact, kernel( models.reading62 ) );
const denseMs = perFrameMedian( tongues, kernel( models.dense96 ) );
const naiveMs = perFrameMedian( tongues, naive( models.reading62 ), BASELINE_RUNS, 1 );

const fmt = ( ms ) => `${ ms.toFixed( 4 ) } ms`;
console.log( `EPG contact + indices per frame, JS (${ source })` );
console.log( `  ${ tongues.length } corrected tongues of ${ rig.vertexCount } vertices, ${ rig.index.length / 3 } triangles; ${ withContact.length } touch the palate` );
console.log( `  kernel, Reading 62, all frames:          median ${ fmt( readingMs ) } per frame (goal < ${ GOAL_MS } ms: ${ readingMs < GOAL_MS ? 'met' : 'NOT met' })` );
console.log( `  kernel, Reading 62, frames with contact: median ${ fmt( contactMs ) } per frame` );
console.log( `  kernel, dense 96, all frames:            median ${ fmt( denseMs ) } per frame` );
console.log( `  baseline (every probe x every triangle): median ${ fmt( naiveMs ) } per frame` );
console.log( `  ratio baseline / kernel: ${ ( naiveMs / readingMs ).toFixed( 1 ) }x` );
if ( sink === 42 ) console.log( '' ); // keeps the work observable
check( 'the kernel\'s frames are the baseline\'s', cellsDiffer === 0 && contacts > 0, `${ cellsDiffer } cells differ, ${ contacts } contacts over both grids` );
