// The workbench's 2D panels (web/src/ui/shared/SagittalPanel.js, SectionsPanel.js) drawn into a
// recording canvas context, from the fitted rig of the shared vectors: what is drawn, where, and
// how it follows the parameters.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { readFileSync } from 'node:fs';
import { dirname, join } from 'node:path';
import { fileURLToPath } from 'node:url';

import { Articulation, parameterDefinitions } from '../../web/src/scene/Articulation.js';
import { TongueRig } from '../../web/src/core/tongue.js';
import { jawPose, POSE_LENGTH } from '../../web/src/core/jaw.js';
import { ParamState } from '../../web/src/core/paramState.js';
import { drawSagittalPanel, fitTransform, MidlineOutline, PANEL_COLORS, sagittalCurve, SAGITTAL_BOX } from '../../web/src/ui/shared/SagittalPanel.js';
import { BoxGeometry, Matrix4 } from 'three';
import { nearArray } from './support/near.js';
import {
	blendingFunctions, coronalSection, drawSectionsPanel, SECTION_NAMES, sectionControls, sectionStations,
} from '../../web/src/ui/workbench/SectionsPanel.js';

const RIG = JSON.parse( readFileSync( join( dirname( fileURLToPath( import.meta.url ) ), '..', 'vectors', 'tongue-surface.json' ), 'utf8' ) ).fixtures.rig;
const LETTERS = RIG.sagittal.control_points.map( ( p ) => p.name );
const SIZE = { width: 380, height: 290 };

/** A canvas 2D context that records every call and property write, in order. */
function recordingContext() {

	const calls = [];
	const state = { lineDash: [] };
	return new Proxy( {}, {
		get( _, key ) {

			if ( key === 'calls' ) return calls;
			if ( key in state ) return state[ key ];
			return ( ...args ) => {

				if ( key === 'setLineDash' ) state.lineDash = args[ 0 ];
				calls.push( { op: key, args, fillStyle: state.fillStyle, strokeStyle: state.strokeStyle, dash: state.lineDash } );

			};

		},
		set( _, key, value ) {

			state[ key ] = value;
			calls.push( { op: 'set', key, value } );
			return true;

		},
	} );

}

const texts = ( ctx ) => ctx.calls.filter( ( c ) => c.op === 'fillText' );
const textAt = ( ctx, text ) => texts( ctx ).find( ( c ) => c.args[ 0 ] === text );

function articulated( params = {} ) {

	const rig = new TongueRig( RIG );
	const state = new ParamState( parameterDefinitions( RIG ) );
	const articulation = new Articulation( rig, state );
	for ( const [ name, value ] of Object.entries( params ) ) state.set( name, value );
	articulation.update( true );
	return articulation;

}

function sagittalScene( articulation, extra = {} ) {

	const rig = articulation.rig;
	return {
		curve: sagittalCurve( rig, articulation.positions, new Float64Array( 2 * rig.stationCount ) ),
		points: articulation.sagittalPoints, letters: LETTERS, hub: articulation.hub, origin: [ 0, - 0.7 ],
		...extra,
	};

}

test( 'the sagittal panel letters every control point, the hub and the origin inside the canvas', () => {

	const ctx = recordingContext();
	drawSagittalPanel( ctx, sagittalScene( articulated() ), SIZE );
	for ( const label of [ ...LETTERS, 'H', 'O' ] ) {

		const call = textAt( ctx, label );
		assert.ok( call, `${ label } is not drawn` );
		const [ , x, y ] = call.args;
		assert.ok( x > 0 && x < SIZE.width && y > 0 && y < SIZE.height, `${ label } at ${ x }, ${ y } is off the canvas` );

	}

	assert.equal( LETTERS.length, 19 );

} );

test( 'the sagittal panel draws anterior to the left and up as up', () => {

	const view = fitTransform( SAGITTAL_BOX, SIZE.width, SIZE.height );
	assert.ok( view.x( 20 ) < view.x( - 40 ), 'the tip side (+x) is on the left' );
	assert.ok( view.y( 10 ) < view.y( - 10 ) );
	assert.ok( Math.abs( ( view.x( 0 ) - view.x( 10 ) ) - ( view.y( 0 ) - view.y( 10 ) ) ) < 1e-9, 'one scale for both axes' );
	const ctx = recordingContext();
	drawSagittalPanel( ctx, sagittalScene( articulated() ), SIZE );
	assert.ok( textAt( ctx, 'B' ).args[ 1 ] < textAt( ctx, 'K' ).args[ 1 ], 'the tip B is left of the root K' );

} );

test( 'the control points are drawn where the articulation put them, and raising the tip raises B', () => {

	const squares = ( ctx ) => ctx.calls.filter( ( c ) => c.op === 'fillRect' && c.args[ 2 ] === 5 );
	const rest = articulated();
	const raised = articulated( { tip_height: 6 } );
	const before = recordingContext();
	const view = drawSagittalPanel( before, sagittalScene( rest ), SIZE );
	const after = recordingContext();
	drawSagittalPanel( after, sagittalScene( raised ), SIZE );
	assert.equal( squares( before ).length, 19 );
	squares( after ).forEach( ( call, k ) => {

		assert.ok( Math.abs( call.args[ 0 ] + 2.5 - view.x( raised.sagittalPoints[ 2 * k ] ) ) < 1e-9 );
		assert.ok( Math.abs( call.args[ 1 ] + 2.5 - view.y( raised.sagittalPoints[ 2 * k + 1 ] ) ) < 1e-9 );

	} );
	const b = LETTERS.indexOf( 'B' );
	const rise = squares( before )[ b ].args[ 1 ] - squares( after )[ b ].args[ 1 ];
	assert.ok( Math.abs( rise - 6 * view.scale ) < 1e-6, `B rose ${ rise } px for 6 mm at ${ view.scale } px/mm` );
	const k = LETTERS.indexOf( 'K' );
	assert.equal( squares( before )[ k ].args[ 1 ], squares( after )[ k ].args[ 1 ], 'the root stays' );

} );

test( 'the tongue curve is one closed path through every station, filled and stroked in the tongue colour', () => {

	const articulation = articulated();
	const ctx = recordingContext();
	drawSagittalPanel( ctx, sagittalScene( articulation ), SIZE );
	const fill = ctx.calls.findIndex( ( c ) => c.op === 'fill' && c.fillStyle === PANEL_COLORS.tongueFill );
	assert.ok( fill > 0 );
	const start = ctx.calls.slice( 0, fill ).map( ( c ) => c.op ).lastIndexOf( 'beginPath' );
	const path = ctx.calls.slice( start, fill ).map( ( c ) => c.op );
	assert.equal( path.filter( ( op ) => op === 'moveTo' || op === 'lineTo' ).length, articulation.rig.stationCount );
	assert.equal( path.at( - 1 ), 'closePath' );

} );

test( 'the uncorrected curve is drawn dotted only when there is one', () => {

	const dotted = ( ctx ) => ctx.calls.filter( ( c ) => c.op === 'stroke' && c.dash.length === 2 && c.dash[ 0 ] === 1.5 );
	const articulation = articulated();
	const without = recordingContext();
	drawSagittalPanel( without, sagittalScene( articulation ), SIZE );
	const withRaw = recordingContext();
	drawSagittalPanel( withRaw, sagittalScene( articulation, { rawCurve: new Float64Array( articulation.rig.stationCount * 2 ) } ), SIZE );
	assert.equal( dotted( without ).length, 0 );
	assert.equal( dotted( withRaw ).length, 1 );

} );

test( 'an outline that rides on the jaw is drawn through the jaw pose', () => {

	const pose = jawPose( 20, RIG.jaw, new Float64Array( POSE_LENGTH ) );
	const ctx = recordingContext();
	const view = drawSagittalPanel( ctx, sagittalScene( articulated(), {
		outlines: [ { segments: Float64Array.of( 20, - 20, 30, - 20 ), count: 1, color: '#123456', pose } ],
	} ), SIZE );
	const i = ctx.calls.findIndex( ( c ) => c.op === 'moveTo' && c.strokeStyle === '#123456' );
	const [ move, line ] = [ ctx.calls[ i ], ctx.calls[ i + 1 ] ];
	const posed = ( x, y ) => [ view.x( pose[ 0 ] * x + pose[ 1 ] * y + pose[ 3 ] ), view.y( pose[ 4 ] * x + pose[ 5 ] * y + pose[ 7 ] ) ];
	for ( const [ call, expected ] of [ [ move, posed( 20, - 20 ) ], [ line, posed( 30, - 20 ) ] ] ) {

		assert.ok( Math.abs( call.args[ 0 ] - expected[ 0 ] ) < 1e-9 && Math.abs( call.args[ 1 ] - expected[ 1 ] ) < 1e-9 );

	}

	assert.ok( posed( 20, - 20 )[ 1 ] > view.y( - 20 ), 'an open jaw carries the chin down' );

} );

test( 'the three sections sit front to back along the upper surface', () => {

	const rig = new TongueRig( RIG );
	const stations = sectionStations( rig );
	const { u, coronal } = blendingFunctions( rig );
	assert.equal( stations.length, 3 );
	assert.ok( u[ stations[ 0 ] ] < u[ stations[ 1 ] ] && u[ stations[ 1 ] ] < u[ stations[ 2 ] ], `stations ${ stations }` );
	for ( const station of stations ) assert.ok( coronal[ station ] > 0.9, `station ${ station } is off the upper surface` );

} );

test( 'the blending functions share every station between the sections, and coronal articulation spares the floor', () => {

	const rig = new TongueRig( RIG );
	const { curves, coronal, letters } = blendingFunctions( rig );
	for ( let i = 0; i < rig.stationCount; i ++ ) {

		const sum = curves[ 0 ][ i ] + curves[ 1 ][ i ] + curves[ 2 ][ i ];
		assert.ok( Math.abs( sum - 1 ) < 1e-9, `station ${ i } blends sum to ${ sum }` );

	}

	assert.ok( Math.min( ...coronal ) < 1e-6 && Math.max( ...coronal ) > 1 - 1e-6 );
	assert.deepEqual( letters.map( ( l ) => l.letter ), LETTERS );
	assert.equal( letters.find( ( l ) => l.letter === 'B' ).u, 0, 'the curve starts at the tip, B' );
	const ordered = letters.slice( 1 ).map( ( l ) => l.u );
	assert.deepEqual( ordered, [ ...ordered ].sort( ( a, b ) => a - b ), 'B to S run along the curve' );

} );

test( 'at rest each coronal section is symmetric about the mid-sagittal plane', () => {

	const articulation = articulated();
	const rig = articulation.rig;
	for ( const station of sectionStations( rig ) ) {

		const points = coronalSection( rig, articulation.positions, station, articulation.hub, articulation.directions, new Float64Array( 2 * ( rig.pageCount + 2 ) ) );
		const n = points.length / 2;
		for ( let k = 0; k < n; k ++ ) {

			assert.ok( Math.abs( points[ 2 * k ] + points[ 2 * ( n - 1 - k ) ] ) < 1e-4, `station ${ station } point ${ k } lateral` );
			assert.ok( Math.abs( points[ 2 * k + 1 ] - points[ 2 * ( n - 1 - k ) + 1 ] ) < 1e-4, `station ${ station } point ${ k } radial` );

		}

		assert.ok( points[ 0 ] < 0 && points[ 2 * n - 2 ] > 0, 'from the right pole (-z) to the left pole (+z)' );
		const controls = sectionControls( rig, articulation.controls, articulation.stationStretch, station, new Float64Array( 2 * rig.controlCount ) );
		const middle = ( rig.controlCount - 1 ) / 2;
		assert.ok( Math.abs( controls[ 2 * middle ] ) < 1e-9, 'the midline control is on the midline' );

	}

} );

test( 'the sections panel draws three labelled sections and a groove deepens the drawn midline', () => {

	const draw = ( params ) => {

		const articulation = articulated( params );
		const rig = articulation.rig;
		const stations = sectionStations( rig );
		const sections = stations.map( ( station ) => ( {
			points: coronalSection( rig, articulation.positions, station, articulation.hub, articulation.directions, new Float64Array( 2 * ( rig.pageCount + 2 ) ) ),
			controls: sectionControls( rig, articulation.controls, articulation.stationStretch, station, new Float64Array( 2 * rig.controlCount ) ),
		} ) );
		const rest = articulated();
		sections.forEach( ( section, s ) => {

			section.rest = coronalSection( rig, rest.positions, stations[ s ], rest.hub, rest.directions, new Float64Array( section.points.length ) );

		} );
		const ctx = recordingContext();
		const views = drawSectionsPanel( ctx, { sections, stations, blends: blendingFunctions( rig ) }, { width: 380, height: 330 } );
		const middle = sections[ 1 ].points;
		const m = middle.length / 2 / 2 | 0;
		return { ctx, midlineY: views.sections[ 1 ].y( middle[ 2 * m + 1 ] ), midlineZ: middle[ 2 * m ] };

	};

	const flat = draw( {} );
	const grooved = draw( { middle_groove_depth: 5 } );
	for ( const name of SECTION_NAMES ) assert.ok( textAt( flat.ctx, name ), `${ name } is not labelled` );
	for ( const letter of LETTERS ) assert.ok( textAt( flat.ctx, letter ), `${ letter } is not on the blending axis` );
	assert.ok( Math.abs( flat.midlineZ ) < 1e-4, 'the middle sample is the midline' );
	assert.ok( grooved.midlineY - flat.midlineY > 2, `a 5 mm groove moved the midline down ${ grooved.midlineY - flat.midlineY } px` );

} );

test( 'a part\'s mid-sagittal outline is its cut by z = 0, posed by its group\'s matrix', () => {

	// A 10 x 6 x 40 mm box centred at ( 30, -2, 0 ): its cut is a 10 x 6 rectangle.
	const box = new BoxGeometry( 10, 6, 40, 1, 1, 2 ).translate( 30, - 2, 0 );
	const outline = new MidlineOutline( '#000000' );
	const matrix = new Matrix4().set( ...jawPose( 15, RIG.jaw, new Float64Array( POSE_LENGTH ) ), 0, 0, 0, 1 );
	outline.update( box.attributes.position.array, box.index.array, matrix.elements );
	assert.ok( outline.count >= 4, `${ outline.count } segments` );
	const xs = [], ys = [];
	for ( let k = 0; k < 4 * outline.count; k += 2 ) {

		xs.push( outline.segments[ k ] );
		ys.push( outline.segments[ k + 1 ] );

	}

	nearArray( [ Math.min( ...xs ), Math.max( ...xs ), Math.min( ...ys ), Math.max( ...ys ) ], [ 25, 35, - 5, 1 ], 1e-6, 'outline bounds (mm, float32)' );
	const pose = jawPose( 15, RIG.jaw, new Float64Array( POSE_LENGTH ) );
	outline.pose.forEach( ( value, k ) => assert.ok( Math.abs( value - pose[ k ] ) < 1e-6, `pose entry ${ k }` ) );
	const scratch = outline.scratch;
	outline.update( box.attributes.position.array, box.index.array, null );
	assert.equal( outline.scratch, scratch, 'the same part again needs no new arrays' );

} );
