// The flat EPG displays drawn through a recording 2D context (no browser): the palatogram, the
// strip over time and the index curves; the clinician's time base; the live EPG of a tongue.
import { test } from 'node:test';
import assert from 'node:assert/strict';

import {
	CODE_BOTH_ON, CODE_ONLY_RECORDING, CODE_ONLY_REFERENCE, drawPalatogram, PALATOGRAM_COLORS, palatogramLayout,
} from '../../web/src/ui/shared/Palatogram.js';
import { drawPalatogramStrip, frameAtX, stripWindow } from '../../web/src/ui/clinician/PalatogramStrip.js';
import { drawIndexPlot, scaleLinear } from '../../web/src/ui/clinician/IndexPlot.js';
import { alignTarget, codesFromRows, frameAtElapsed, framesFromRows, indexTracks } from '../../web/src/ui/clinician/clinicianFrames.js';
import { parseTargetName } from '../../web/src/ui/shared/targets.js';
import { createEpgLive } from '../../web/src/scene/EpgLive.js';
import { debugObject, installDebug } from '../../web/src/debug.js';
import { TongueRig } from '../../web/src/core/tongue.js';
import { recordingContext } from './support/recordingContext.js';
import { correctVertices } from '../../web/src/core/collision.js';
import { decodeCollisionTables } from '../../web/src/core/tables.js';
import { near, nearArray, readVectors } from './support/vectors.js';

const CONTACTS = readVectors( 'epg-contacts.json' );
const { fixtures: FIXTURES } = CONTACTS;

const ROWS_T = [ '01111110', '10000001', '10000001', '00000000', '00000000', '00000000', '00000000', '00000000' ];

test( 'a palatogram draws a square per contact, a dot per other electrode, nothing at the R1 corners', () => {

	const ctx = recordingContext();
	const frame = framesFromRows( [ ROWS_T ] );
	const layout = drawPalatogram( ctx, frame, { width: 160, height: 160 } );
	const squares = ctx.calls.filter( ( c ) => c.name === 'fillRect' && c.fillStyle === PALATOGRAM_COLORS.contact );
	const dots = ctx.calls.filter( ( c ) => c.name === 'arc' );
	assert.equal( squares.length, 10 );
	assert.equal( dots.length, 62 - 10 );
	// Every square is centred on the cell of a contact; R1 is the top row, column 1 the left.
	const centres = squares.map( ( c ) => [ c.args[ 0 ] + c.args[ 2 ] / 2, c.args[ 1 ] + c.args[ 3 ] / 2 ] );
	const expected = [];
	ROWS_T.forEach( ( row, r ) => [ ...row ].forEach( ( v, c ) => v === '1' && expected.push( layout.centre( r, c ) ) ) );
	assert.equal( centres.length, expected.length );
	centres.forEach( ( p, k ) => nearArray( p, expected[ k ], 1e-9, `square ${ k } centre (px)` ) );
	const [ , r1y ] = layout.centre( 0, 3 );
	const [ , r8y ] = layout.centre( 7, 3 );
	assert.ok( r1y < r8y, 'the front row is drawn at the top' );
	const [ c1x ] = layout.centre( 3, 0 );
	for ( const call of dots ) assert.notDeepEqual( [ call.args[ 0 ], call.args[ 1 ] ].map( Math.round ), layout.centre( 0, 0 ).map( Math.round ) );
	assert.ok( c1x < layout.centre( 3, 7 )[ 0 ] );

} );

test( 'a palatogram of comparison codes marks each side of a disagreement apart', () => {

	const ctx = recordingContext();
	const codes = new Uint8Array( 64 );
	codes[ 9 ] = CODE_BOTH_ON;
	codes[ 10 ] = CODE_ONLY_RECORDING;
	codes[ 11 ] = CODE_ONLY_REFERENCE;
	codes[ 0 ] = 9;
	drawPalatogram( ctx, null, { width: 100, height: 120, codes, label: 'agreement' } );
	assert.equal( ctx.calls.filter( ( c ) => c.name === 'fillRect' && c.fillStyle === PALATOGRAM_COLORS.contact ).length, 1 );
	assert.equal( ctx.calls.filter( ( c ) => c.name === 'fillRect' && c.fillStyle === PALATOGRAM_COLORS.onlyRecording ).length, 1 );
	assert.equal( ctx.calls.filter( ( c ) => c.name === 'strokeRect' && c.strokeStyle === PALATOGRAM_COLORS.onlyReference ).length, 1 );
	assert.equal( ctx.calls.filter( ( c ) => c.name === 'arc' ).length, 59 );
	assert.ok( ctx.calls.some( ( c ) => c.name === 'fillText' && c.args[ 0 ] === 'agreement' ) );

} );

test( 'palatogram cells are square and fit inside the box', () => {

	const layout = palatogramLayout( { x: 10, y: 20, width: 300, height: 150 } );
	assert.ok( layout.x0 >= 10 && layout.y0 >= 20 );
	assert.ok( layout.x0 + 8 * layout.pitch <= 310 && layout.y0 + 8 * layout.pitch <= 170 );

} );

test( 'the strip shows the window of frames around the current one and maps clicks back to frames', () => {

	assert.deepEqual( stripWindow( 100, 50, 400, 100 ), { first: 48, count: 4, size: 85 } );
	assert.deepEqual( stripWindow( 3, 2, 400, 100 ), { first: 0, count: 3, size: 85 } );
	assert.equal( stripWindow( 100, 99, 400, 100 ).first, 96 );
	assert.equal( frameAtX( 90, 100, 50, 400, 100 ), 49 );
	assert.equal( frameAtX( 399, 100, 50, 400, 100 ), - 1 );
	const ctx = recordingContext();
	const frames = framesFromRows( [ ROWS_T, ROWS_T, ROWS_T.map( () => '00000000' ) ] );
	const drawn = drawPalatogramStrip( ctx, frames, 3, { width: 400, height: 100, current: 2, t_s: [ 1.0, 1.005, 1.01 ] } );
	assert.equal( drawn.count, 3 );
	assert.equal( ctx.calls.filter( ( c ) => c.name === 'fillRect' && c.fillStyle === PALATOGRAM_COLORS.contact ).length, 20 );
	assert.deepEqual( ctx.calls.filter( ( c ) => c.name === 'fillText' ).map( ( c ) => c.args[ 0 ] ), [ '0 ms', '5 ms', '10 ms' ] );
	// The current frame (the third) is framed.
	const frame = ctx.calls.filter( ( c ) => c.name === 'strokeRect' && c.strokeStyle === PALATOGRAM_COLORS.onlyRecording );
	assert.equal( frame.length, 1 );
	near( frame[ 0 ].args[ 0 ], 2 * 85 + 1, 0.5, 'the frame of the third palatogram (px)' );

} );

test( 'index curves hold each frame until the next and put the cursor at the current time', () => {

	const ctx = recordingContext();
	const t_s = [ 0, 0.01, 0.02 ];
	const geometry = drawIndexPlot( ctx, {
		width: 400, height: 118, t_s, panels: [ 'percent' ], current: 1,
		tracks: [ { label: 'recording', color: '#000', indices: { percent: [ 0, 50, 100 ] } },
			{ label: 'target', color: '#f00', dash: [ 6, 4 ], indices: { percent: [ 10, 10, 10 ] } } ],
	} );
	const y = scaleLinear( 0, 100, 4 + 100 - 8, 4 );
	const line = ctx.calls.filter( ( c ) => ( c.name === 'moveTo' || c.name === 'lineTo' ) && c.strokeStyle === '#000' ).slice( 0, 5 );
	const steps = [
		[ geometry.x( 0 ), y( 0 ) ], [ geometry.x( 0.01 ), y( 0 ) ], [ geometry.x( 0.01 ), y( 50 ) ],
		[ geometry.x( 0.02 ), y( 50 ) ], [ geometry.x( 0.02 ), y( 100 ) ],
	];
	assert.equal( line.length, steps.length );
	line.forEach( ( c, k ) => nearArray( c.args, steps[ k ], 1e-9, `step ${ k } (px)` ) );
	assert.ok( ctx.calls.some( ( c ) => c.name === 'stroke' && c.strokeStyle === '#f00' && c.dash.length === 2 ), 'the target is dashed' );
	const cursor = ctx.calls.filter( ( c ) => c.strokeStyle === '#b4384a' && c.name === 'moveTo' );
	assert.equal( cursor.length, 1 );
	near( cursor[ 0 ].args[ 0 ], geometry.x( 0.01 ), 1e-9, 'cursor x (px)' );

} );

test( 'playback finds the frame showing at a time, and targets align as the compare API aligns them', () => {

	const t = Float64Array.of( 10, 10.005, 10.01, 10.02 );
	assert.equal( frameAtElapsed( t, 0 ), 0 );
	assert.equal( frameAtElapsed( t, 0.0049 ), 0 );
	assert.equal( frameAtElapsed( t, 0.005 ), 1 );
	assert.equal( frameAtElapsed( t, 0.019 ), 2 );
	assert.equal( frameAtElapsed( t, 5 ), 3 );
	assert.deepEqual( Array.from( alignTarget( t, 1 ) ), [ 0, 0, 0, 0 ] );
	assert.deepEqual( Array.from( alignTarget( t, 4 ) ), [ 0, 1, 2, 3 ] );
	assert.deepEqual( Array.from( alignTarget( t, 2, [ 0, 0.01 ] ) ), [ 0, 0, 1, 1 ] );
	const codes = codesFromRows( [ [ '90000009', '12300000', '00000000', '00000000', '00000000', '00000000', '00000000', '00000000' ] ] );
	assert.deepEqual( Array.from( codes.subarray( 0, 11 ) ), [ 9, 0, 0, 0, 0, 0, 0, 9, 1, 2, 3 ] );
	const tracks = indexTracks( framesFromRows( [ ROWS_T ] ), 1 );
	assert.equal( tracks.contacts[ 0 ], 10 );
	assert.deepEqual( parseTargetName( 'pose:12' ), { kind: 'pose', id: '12' } );
	assert.equal( parseTargetName( '12' ), null );

} );

test( 'the live EPG of a corrected tongue reports its rows, percent and indices in window.glasshead', () => {

	installDebug( globalThis );
	const rig = new TongueRig( FIXTURES.rig );
	const tables = decodeCollisionTables( readVectors( FIXTURES.tables.file ) );
	const live = createEpgLive( { layout: FIXTURES.layout, tongueTriangles: rig.index, vertexCount: rig.vertexCount, dense: true } );
	const unregister = live.registerDebug();
	const seen = [];
	live.onUpdate( ( l ) => seen.push( l.contacted ) );
	const c = CONTACTS.cases.find( ( k ) => 'params' in k.input && k.expected.reading62.contacted > 20 );
	const surface = rig.createSurface();
	rig.evaluate( rig.valuesFrom( c.input.params ), surface );
	correctVertices( surface.positions, rig.vertexCount, tables, null, null );
	live.update( surface.positions );
	const report = debugObject().epg;
	assert.deepEqual( report.rows, c.expected.reading62.rows );
	assert.deepEqual( report.dense, c.expected.dense96.rows );
	assert.equal( report.contacted, c.expected.reading62.contacted );
	// Rounded to 3 decimals for the report; 1e-9 is far below that step.
	near( report.percent, Math.round( 100000 * c.expected.reading62.contacted / 62 ) / 1000, 1e-9, 'percent' );
	assert.equal( report.indices.contacts, c.expected.reading62.contacted );
	assert.deepEqual( seen, [ c.expected.reading62.contacted ] );
	live.clear();
	assert.equal( debugObject().epg.contacted, 0 );
	unregister();
	assert.equal( debugObject().epg, undefined );

} );

test( 'the 3D electrodes draw contacted ones as squares on the palate and the others as dots', async () => {

	const { Electrodes } = await import( '../../web/src/scene/Electrodes.js' );
	const { Matrix4, Plane, Vector3 } = await import( 'three' );
	const grid = FIXTURES.layout.grids.reading62;
	const clip = new Plane( new Vector3( 0, 0, 1 ), 0 );
	const electrodes = new Electrodes( grid, { clippingPlanes: [ clip ] } );
	assert.equal( electrodes.dots.count, 62 );
	assert.equal( electrodes.squares.count, 0 );
	const frame = framesFromRows( [ ROWS_T ] );
	electrodes.show( frame );
	assert.equal( electrodes.squares.count, 10 );
	assert.equal( electrodes.dots.count, 52 );
	assert.equal( electrodes.ghostSquares.count, 10 );
	// Each square sits on its electrode, lifted toward the tongue, its face along the normal.
	const m = new Matrix4();
	const placed = [];
	for ( let s = 0; s < 10; s ++ ) {

		electrodes.squares.getMatrixAt( s, m );
		placed.push( new Vector3().setFromMatrixPosition( m ) );

	}

	const contacted = grid.electrodes.filter( ( e ) => frame[ e.cell ] === 1 );
	contacted.forEach( ( e, s ) => {

		const expected = new Vector3().fromArray( e.position ).addScaledVector( new Vector3().fromArray( e.normal ), 0.2 );
		assert.ok( placed[ s ].distanceTo( expected ) < 1e-4, e.id );

	} );
	electrodes.squares.getMatrixAt( 0, m );
	const axis = new Vector3().setFromMatrixColumn( m, 2 ).normalize();
	assert.ok( axis.dot( new Vector3().fromArray( contacted[ 0 ].normal ) ) > 0.9999 );
	assert.deepEqual( electrodes.dots.material.clippingPlanes, [ clip ] );
	assert.equal( electrodes.ghostDots.visible, false );
	assert.equal( electrodes.setXray( true ), true );
	assert.equal( electrodes.setXray( true ), false );
	assert.equal( electrodes.ghostDots.material.depthTest, false );
	electrodes.show( null );
	assert.equal( electrodes.squares.count, 0 );
	electrodes.dispose();

} );
