// The workbench's Observation and Phoneme target groups without a browser: their controls
// (web/src/ui/workbench/ObservationControl.js, PhonemeChooser.js) over a fake API, on the fitted tongue of
// the shared vectors; the ray error (web/src/core/rayError.js) on small exact cases; the sagittal
// overlay drawn into a recording context and the 3D layer (web/src/scene/ObservationLayer.js)
// without a renderer.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { readFileSync } from 'node:fs';
import { dirname, join } from 'node:path';
import { fileURLToPath } from 'node:url';

import { createApi } from '../../web/src/api.js';
import { Articulation, parameterDefinitions } from '../../web/src/scene/Articulation.js';
import { TongueRig } from '../../web/src/core/tongue.js';
import { ParamState } from '../../web/src/core/paramState.js';
import { createRayFan, rayFirstHits } from '../../web/src/core/rayFirstHit.js';
import { createRayError, PART_OUTLINE, PART_SURFACE, rayError, STAT_MAX, STAT_MISSES, STAT_RMS } from '../../web/src/core/rayError.js';
import { assignParams, formatMm, ObservationControl } from '../../web/src/ui/workbench/ObservationControl.js';
import { drawObservationSagittal } from '../../web/src/ui/workbench/ObservationOverlay.js';
import { PhonemeTargetControl } from '../../web/src/ui/workbench/PhonemeChooser.js';
import { OBSERVATION_COLORS, ObservationLayer, sphereRadius } from '../../web/src/scene/ObservationLayer.js';
import { Color, Matrix4 } from 'three';
import { debugObject, registerDebug } from '../../web/src/debug.js';
import { near } from './support/near.js';

const RIG = JSON.parse( readFileSync( join( dirname( fileURLToPath( import.meta.url ) ), '..', 'vectors', 'tongue-surface.json' ), 'utf8' ) ).fixtures.rig;

/** The fit's result in the fake observation: a raised, advanced tongue with the jaw a little open. */
const AFTER = Object.freeze( { tip_height: 4, blade_height: 3, dorsum_height: 5, dorsum_advancement: 2, jaw_opening: 6 } );

function articulated() {

	const rig = new TongueRig( RIG );
	const state = new ParamState( parameterDefinitions( RIG ) );
	const articulation = new Articulation( rig, state );
	articulation.update( true );
	return articulation;

}

/**
 * An observation whose outline is the posed tongue's own crossings at AFTER (so the fit's
 * result is exact), along rays from the hub at 10 degree steps over the dorsum, and a few
 * surface points 1 mm outside the same tongue.
 */
function fakeObservation() {

	const articulation = articulated();
	articulation.state.assign( AFTER );
	articulation.update();
	const hub = [ articulation.rig.hub[ 0 ], articulation.rig.hub[ 1 ], 0 ];
	const angles = Array.from( { length: 16 }, ( _, k ) => ( - 10 + 10 * k ) * Math.PI / 180 );
	const directions = angles.flatMap( ( a ) => [ hub[ 0 ] + 10 * Math.cos( Math.PI - a ), hub[ 1 ] + 10 * Math.sin( Math.PI - a ), 0 ] );
	const fan = createRayFan( hub, directions );
	const t = new Float64Array( fan.count );
	rayFirstHits( fan, articulation.positions, articulation.triangles, articulation.triangles.length / 3, t );
	const outline = angles.map( ( _, k ) => [ 0, 1 ].map( ( i ) => hub[ i ] + t[ k ] * fan.directions[ 3 * k + i ] ) );
	const surface = [ 100, 900, 1700 ].map( ( v ) => [ 0, 1, 2 ].map( ( i ) => {

		const d = articulation.positions[ 3 * v + i ] - hub[ i ];
		return hub[ i ] + d * ( 1 + 1 / Math.hypot( ...[ 0, 1, 2 ].map( ( j ) => articulation.positions[ 3 * v + j ] - hub[ j ] ) ) );

	} ) );
	const neutral = Object.fromEntries( RIG.parameters.map( ( p ) => [ p.name, p.neutral ] ) );
	return {
		name: 'jd3-t-a', source: 'vtl-jd3', label: 'JD3 /t/ closure in /a/ context', origin: hub, outline, surface,
		before: { params: neutral }, after: { params: { ...neutral, ...AFTER }, rms_mm: 0.01, max_error_mm: 0.02 },
		plot_url: '/assets/build/fits/jd3-t-a.svg',
	};

}

/** A client whose fetch answers `routes` ({ path: body }) and 404 for anything else; it records the paths asked for. */
function fakeApi( routes, { delays = {} } = {} ) {

	const asked = [];
	const fetchImpl = async ( url ) => {

		const path = url.replace( '/api/v1/', '' );
		asked.push( path );
		if ( delays[ path ] ) await new Promise( ( resolve ) => setTimeout( resolve, delays[ path ] ) );
		const body = routes[ path ];
		if ( body === undefined ) return { ok: false, status: 404, statusText: 'Not Found', json: async () => ( { detail: `no observation "${ decodeURIComponent( path.split( '/' ).pop() ) }"` } ) };
		return { ok: true, status: 200, json: async () => structuredClone( body ) };

	};

	return { api: createApi( { fetchImpl } ), asked };

}

function observationRoutes( observation = fakeObservation() ) {

	return {
		observations: { observations: [ { name: observation.name, source: observation.source, label: observation.label, has_surface: true, rms_mm: 0.01 } ] },
		[ `observations/${ observation.name }` ]: observation,
	};

}

test( 'the ray error is signed: positive where the tongue lies beyond the observed point, and a miss ends at the origin', () => {

	// A square at x = 10 facing the origin; P at x = 5 (the surface beyond it), x = 20 (short of
	// it) and a surface point behind the origin that no ray from it reaches.
	const positions = Float32Array.of( 10, - 9, - 9, 10, 9, - 9, 10, 9, 9, 10, - 9, 9 );
	const triangles = Uint32Array.of( 0, 1, 2, 0, 2, 3 );
	const model = createRayError( [ 0, 0, 0 ], [ [ 5, 1 ], [ 20, - 2 ] ], [ [ - 4, 0, 3 ] ] );
	rayError( model, positions, triangles, 2 );
	near( model.signed[ 0 ], Math.hypot( 5, 1 ), 1e-9, 'P at x = 5: Q at x = 10, one |OP| beyond' );
	near( model.signed[ 1 ], - Math.hypot( 20, 2 ) / 2, 1e-9, 'P at x = 20: Q halfway, short' );
	near( model.q[ 3 ], 10, 1e-9, 'Q of the second ray lies on the square' );
	near( model.q[ 5 ], 0, 0, 'an outline point is at z = 0 and so is its Q' );
	assert.deepEqual( Array.from( model.q.subarray( 6, 9 ) ), [ 0, 0, 0 ], 'a miss ends at the origin' );
	near( model.signed[ 2 ], - 5, 1e-9, 'a miss: the whole |OP|, short' );
	near( model.stats[ PART_OUTLINE + STAT_RMS ], Math.sqrt( ( model.signed[ 0 ] ** 2 + model.signed[ 1 ] ** 2 ) / 2 ), 1e-9, 'outline RMS' );
	near( model.stats[ PART_OUTLINE + STAT_MAX ], Math.hypot( 20, 2 ) / 2, 1e-9, 'outline largest error' );
	assert.equal( model.stats[ PART_OUTLINE + STAT_MISSES ], 0 );
	assert.equal( model.stats[ PART_SURFACE + STAT_MISSES ], 1 );

} );

test( 'spheres grow with the error from 0.25 mm and stop growing at 2.5 mm', () => {

	near( sphereRadius( 0 ), 0.25, 1e-12, 'no error' );
	near( sphereRadius( - 2 ), 0.75, 1e-12, '2 mm short' );
	near( sphereRadius( 40 ), 2.5, 1e-12, 'capped' );

} );

test( 'choosing an observation fetches it by name and sets every parameter to the fit\'s result, where its outline error is nil', async () => {

	const { api, asked } = fakeApi( observationRoutes() );
	const articulation = articulated();
	const state = articulation.state;
	const changes = [];
	state.onChange( ( names ) => changes.push( names ) ); // what the sliders listen to
	const control = new ObservationControl( { api, articulation } );
	const entries = await control.list();
	assert.deepEqual( entries.map( ( e ) => e.label ), [ 'JD3 /t/ closure in /a/ context' ] );
	await control.choose( 'jd3-t-a' );
	assert.deepEqual( asked, [ 'observations', 'observations/jd3-t-a' ] );
	for ( const [ name, value ] of Object.entries( AFTER ) ) near( state.get( name ), value, 1e-6, name );
	assert.equal( changes.length, 1, 'one change of the state: the sliders follow it' );
	const report = control.report();
	assert.equal( report.name, 'jd3-t-a' );
	assert.equal( report.state, 'after' );
	assert.equal( report.rays, 16 );
	assert.equal( report.surface.rays, 3 );
	assert.ok( report.rmsMm < 1e-3, `the outline was made from this tongue: RMS ${ report.rmsMm } mm` );
	near( report.surface.rmsMm, 1, 1e-3, 'the surface points lie 1 mm outside the tongue' );
	assert.equal( report.fitRmsMm, 0.01 );

} );

test( 'Before and After switch every parameter, the error follows, and moving a slider makes it "edited"', async () => {

	const { api } = fakeApi( observationRoutes() );
	const articulation = articulated();
	const control = new ObservationControl( { api, articulation } );
	await control.choose( 'jd3-t-a' );
	const after = control.report();
	control.show( 'before' );
	const before = control.report();
	assert.equal( before.state, 'before' );
	assert.equal( articulation.state.get( 'tip_height' ), 0, 'back to the start: neutral' );
	assert.ok( before.rmsMm > after.rmsMm + 1, `before ${ before.rmsMm } mm, after ${ after.rmsMm } mm` );
	assert.ok( before.maxMm >= before.rmsMm );
	articulation.state.set( 'tip_height', 2 );
	assert.equal( control.report().state, 'edited' );
	control.show( 'after' );
	assert.equal( control.report().state, 'after' );
	near( control.report().rmsMm, after.rmsMm, 1e-9, 'the same pose, the same error' );

} );

test( 'the errors are recomputed when the tongue changes, not in frames where nothing moved', async () => {

	const { api } = fakeApi( observationRoutes() );
	const articulation = articulated();
	const control = new ObservationControl( { api, articulation } );
	await control.choose( 'jd3-t-a' );
	const updates = control.report().updates;
	for ( let frame = 0; frame < 5; frame ++ ) articulation.update();
	assert.equal( control.report().updates, updates, 'still frames recompute nothing' );
	articulation.state.set( 'dorsum_height', 8 );
	articulation.update();
	assert.equal( control.report().updates, updates + 1 );
	assert.notEqual( control.report().rmsMm, 0 );
	control.dispose();
	articulation.state.set( 'dorsum_height', 7 );
	articulation.update();
	assert.equal( control.report().updates, updates + 1, 'a disposed control no longer listens' );

} );

test( 'an unknown observation is refused with the server\'s message and changes nothing', async () => {

	const { api } = fakeApi( observationRoutes() );
	const articulation = articulated();
	const control = new ObservationControl( { api, articulation } );
	const version = articulation.state.version;
	await assert.rejects( control.choose( 'jd3-zz' ), /HTTP 404: no observation "jd3-zz"/ );
	assert.equal( articulation.state.version, version );
	assert.equal( control.report().name, null );

} );

test( 'when two observations are chosen quickly, the later choice wins', async () => {

	const first = fakeObservation();
	const second = { ...fakeObservation(), name: 'jd3-k-a', label: 'JD3 /k/', after: { params: { tip_height: - 3 }, rms_mm: 0.5 } };
	const routes = { ...observationRoutes( first ), [ `observations/${ second.name }` ]: second };
	const { api } = fakeApi( routes, { delays: { 'observations/jd3-t-a': 50 } } );
	const articulation = articulated();
	const control = new ObservationControl( { api, articulation } );
	const slow = control.choose( 'jd3-t-a' );
	await control.choose( 'jd3-k-a' );
	assert.equal( await slow, null );
	assert.equal( control.report().name, 'jd3-k-a' );
	assert.equal( articulation.state.get( 'tip_height' ), - 3 );

} );

test( 'window.glasshead.observation reports the name, state, rays and errors', async () => {

	const { api } = fakeApi( observationRoutes() );
	const articulation = articulated();
	const control = new ObservationControl( { api, articulation } );
	const unregister = registerDebug( 'observation', () => control.report() );
	await control.list();
	assert.deepEqual( { ...debugObject().observation }, { listed: 1, overlay: true, updates: 0, name: null, state: null } );
	await control.choose( 'jd3-t-a' );
	control.show( 'before' );
	const shown = debugObject().observation;
	for ( const key of [ 'name', 'state', 'rays', 'rmsMm', 'maxMm' ] ) assert.ok( key in shown, key );
	assert.equal( shown.state, 'before' );
	assert.ok( Object.isFrozen( shown ) );
	unregister();

} );

test( 'the sagittal overlay draws a vector and a disc per outline ray, coloured by its sign, and the observed outline dashed', async () => {

	const { api } = fakeApi( observationRoutes() );
	const articulation = articulated();
	const control = new ObservationControl( { api, articulation } );
	await control.choose( 'jd3-t-a' );
	control.show( 'before' );
	const calls = [];
	const ctx = new Proxy( {}, {
		get: ( _, key ) => ( ...args ) => calls.push( { op: key, args } ),
		set: ( _, key, value ) => calls.push( { op: 'set', key, value } ),
	} );
	drawObservationSagittal( ctx, control.model, { width: 380, height: 290 } );
	assert.equal( calls.filter( ( c ) => c.op === 'arc' ).length, 16 );
	assert.equal( calls.filter( ( c ) => c.op === 'stroke' ).length, 16 + 1 );
	const colours = new Set( calls.filter( ( c ) => c.op === 'set' && c.key === 'fillStyle' ).map( ( c ) => c.value ) );
	const signs = new Set( Array.from( control.model.signed.subarray( 0, 16 ), ( e ) => ( e > 0 ? OBSERVATION_COLORS.beyond : OBSERVATION_COLORS.short ) ) );
	assert.deepEqual( colours, signs );
	for ( const c of calls.filter( ( c ) => c.op === 'arc' ) ) assert.ok( c.args[ 0 ] > 0 && c.args[ 0 ] < 380 && c.args[ 1 ] > 0 && c.args[ 1 ] < 290, 'inside the panel' );

} );

test( 'a phoneme target sets every parameter the state has, names itself, and is "edited" once a slider moves', async () => {

	const target = {
		arpabet: 'T', ipa: 't', kind: 'stop', examples: [ 'tea' ], source: { shapes: [ 'tt-a' ] },
		params: { tip_height: 7.5, blade_height: 4, jaw_opening: 3, lip_rounding: 0.2, velum_opening: 0 },
	};
	const { api, asked } = fakeApi( { phonemes: { phonemes: [ target ] }, 'phonemes/T': target } );
	const articulation = articulated();
	articulation.state.set( 'dorsum_height', 5 );
	const control = new PhonemeTargetControl( { api, state: articulation.state } );
	await control.list();
	await control.choose( 'T' );
	assert.deepEqual( asked, [ 'phonemes', 'phonemes/T' ] );
	near( articulation.state.get( 'tip_height' ), 7.5, 1e-6, 'tip height' );
	near( articulation.state.get( 'jaw_opening' ), 3, 1e-6, 'jaw opening' );
	assert.equal( articulation.state.get( 'dorsum_height' ), 0, 'a parameter the target leaves out goes back to neutral' );
	const report = control.report();
	assert.deepEqual( { symbol: report.symbol, label: report.label, state: report.state }, { symbol: 'T', label: '/t/ T as in "tea"', state: 'target' } );
	assert.deepEqual( report.ignored, [ 'lip_rounding', 'velum_opening' ], 'this state has no lips or velum' );
	articulation.state.set( 'tip_height', 6 );
	assert.equal( control.report().state, 'edited' );

} );

test( 'a target out of range is refused whole, and readouts show two decimals', () => {

	const state = articulated().state;
	assert.throws( () => assignParams( state, { tip_height: 40, blade_height: 2 } ), /tip_height = 40 is outside its range/ );
	assert.equal( state.get( 'blade_height' ), 0 );
	assert.deepEqual( assignParams( state, { blade_height: 2, nasal_port: 1 } ), [ 'nasal_port' ] );
	assert.equal( formatMm( 1.234 ), '1.23 mm' );
	assert.equal( formatMm( NaN ), '–' );

} );

test( 'the 3D layer draws a vector from each P to its Q and a sphere at P sized and coloured by the error, the outline in the cutaway and the surface on the whole tongue', () => {

	const positions = Float32Array.of( 10, - 9, - 9, 10, 9, - 9, 10, 9, 9, 10, - 9, 9 );
	const model = createRayError( [ 0, 0, 0 ], [ [ 5, 1 ], [ 20, - 2 ] ], [ [ 12, 0, 3 ] ] );
	rayError( model, positions, Uint32Array.of( 0, 1, 2, 0, 2, 3 ), 2 );
	let cut = true;
	const layer = new ObservationLayer( { isCut: () => cut } );
	layer.setModel( model );
	const [ outline, surface ] = layer.parts;
	assert.deepEqual( [ outline.count, surface.count ], [ 2, 1 ] );
	const line = outline.vectors.geometry.attributes.position.array;
	assert.deepEqual( Array.from( line.subarray( 0, 3 ) ), [ 5, 1, 0 ], 'from P' );
	near( line[ 3 ], 10, 1e-6, 'to Q on the square' );
	const matrix = new Matrix4();
	const colour = new Color();
	for ( let k = 0; k < 2; k ++ ) {

		outline.spheres.getMatrixAt( k, matrix );
		near( matrix.elements[ 0 ], sphereRadius( model.signed[ k ] ), 1e-6, `sphere ${ k } radius` );
		near( matrix.elements[ 12 ], model.points[ 3 * k ], 1e-6, `sphere ${ k } at P` );
		outline.spheres.getColorAt( k, colour );
		assert.equal( `#${ colour.getHexString() }`, k === 0 ? OBSERVATION_COLORS.beyond : OBSERVATION_COLORS.short );

	}

	outline.points.onBeforeRender();
	surface.spheres.onBeforeRender();
	assert.equal( outline.points.material.depthTest, false, 'over everything while the cutaway shows' );
	assert.equal( surface.spheres.material.colorWrite, false, 'the surface is left out of the cutaway' );
	cut = false;
	outline.points.onBeforeRender();
	surface.spheres.onBeforeRender();
	assert.equal( outline.points.material.depthTest, true, 'inside the whole tongue without it' );
	assert.equal( surface.spheres.material.colorWrite, true, 'the surface shows on the whole tongue' );
	layer.dispose();
	assert.equal( layer.parts.length, 0 );

} );
