// The area function's plot (web/src/ui/shared/AreaFunctionPlot.js): steps from the glottis to the
// lips in proportion to the sections' lengths, areas on a square-root scale, shut sections marked,
// drawn into a recording 2D context.
import { test } from 'node:test';
import assert from 'node:assert/strict';

import { areaFunction, chainPart, createAreaFunction } from '../../web/src/core/areaFunction.js';
import { AREA_COLORS, AREA_TOP_MM2, areaSteps, drawAreaFunction } from '../../web/src/ui/shared/AreaFunctionPlot.js';

/** A channel 10 mm high with a round tongue pressed into its roof at x = -20. */
function tube() {

	const stations = Float64Array.from( { length: 42 }, ( _, k ) => ( k % 2 ? 0 : - 60 + 2 * k ) );
	const floor = [ chainPart( [ - 70, - 5, 40, - 5 ], false ), chainPart( Array.from( { length: 48 }, ( _, k ) => ( k % 2 ? 1 + 8 * Math.sin( Math.PI * ( k - 1 ) / 24 ) : - 20 + 8 * Math.cos( Math.PI * k / 24 ) ) ), true ) ];
	const roof = [ chainPart( [ - 70, 5, 40, 5 ], false ) ];
	return areaFunction( stations, floor, roof, { incisorX: 30, uvulaY: - 100, lipFrontX: 0, lipRounding: 0 }, createAreaFunction( 21 ) );

}

test( 'the steps run from the glottis to the lips, wider sections higher, the tongue\'s shut ones marked', () => {

	const t = tube();
	const { steps, baseline, lengthMm } = areaSteps( t, 400, 160 );
	assert.equal( steps.length, t.count );
	for ( let k = 1; k < steps.length; k ++ ) assert.ok( Math.abs( steps[ k ].x0 - steps[ k - 1 ].x1 ) < 1e-9 && steps[ k ].x1 > steps[ k ].x0 );
	assert.ok( Math.abs( lengthMm - t.lengths.reduce( ( a, b ) => a + b, 0 ) ) < 1e-9 );
	assert.ok( steps.some( ( s ) => s.shut ) && steps.some( ( s ) => ! s.shut ) );
	for ( const s of steps ) assert.ok( s.y <= baseline );
	const shut = steps.find( ( s ) => s.shut ), open = steps[ 1 ];
	assert.ok( shut.y > open.y, 'a shut section is drawn lower than an open one' );
	// The square-root scale: a quarter of the top area is half the height.
	const { y } = areaSteps( t, 400, 160 );
	assert.ok( Math.abs( ( baseline - y( AREA_TOP_MM2 / 4 ) ) - ( baseline - y( AREA_TOP_MM2 ) ) / 2 ) < 1e-9 );

} );

test( 'drawing fills the air, marks the shut sections red and names the ends', () => {

	const calls = [];
	const ctx = new Proxy( { fillStyle: '', strokeStyle: '' }, {
		get: ( target, name ) => ( name in target ? target[ name ] : ( ...args ) => calls.push( { name, args, fillStyle: target.fillStyle } ) ),
		set: ( target, name, value ) => ( ( target[ name ] = value ), true ),
	} );
	drawAreaFunction( ctx, tube(), { width: 400, height: 160 } );
	assert.ok( calls.some( ( c ) => c.name === 'fill' && c.fillStyle === AREA_COLORS.air ) );
	assert.ok( calls.some( ( c ) => c.name === 'fillRect' && c.fillStyle === AREA_COLORS.shut ) );
	const texts = calls.filter( ( c ) => c.name === 'fillText' ).map( ( c ) => c.args[ 0 ] );
	assert.ok( texts.includes( 'glottis' ) && texts.some( ( t ) => t.startsWith( 'lips' ) ), texts.join( ', ' ) );

} );

test( 'with the port open the nose is drawn dashed from the junction and named; without it, not', () => {

	const record = () => {

		const calls = [];
		const ctx = new Proxy( { fillStyle: '', strokeStyle: '' }, {
			get: ( target, name ) => ( name in target ? target[ name ] : ( ...args ) => calls.push( { name, args, strokeStyle: target.strokeStyle } ) ),
			set: ( target, name, value ) => ( ( target[ name ] = value ), true ),
		} );
		return { ctx, calls };

	};

	const t = tube();
	const nasal = { at: 5, lengths: [ 6, 6, 6 ], areas: [ 40, 300, 80 ] };
	const open = record();
	drawAreaFunction( open.ctx, t, { width: 400, height: 160 }, nasal );
	const strokes = open.calls.filter( ( c ) => c.name === 'stroke' && c.strokeStyle === AREA_COLORS.nose );
	assert.equal( strokes.length, 1 );
	assert.ok( open.calls.some( ( c ) => c.name === 'setLineDash' && c.args[ 0 ].length === 2 ) );
	const from = open.calls.find( ( c, k ) => c.name === 'moveTo' && open.calls[ k - 1 ]?.name === 'beginPath' && open.calls.slice( k ).some( ( d ) => d.strokeStyle === AREA_COLORS.nose ) && c.args[ 0 ] === areaSteps( t, 400, 160 ).steps[ 5 ].x0 );
	assert.ok( from, 'the nose starts where its junction is' );
	assert.ok( open.calls.some( ( c ) => c.name === 'fillText' && c.args[ 0 ] === 'nose' ) );
	const shut = record();
	drawAreaFunction( shut.ctx, t, { width: 400, height: 160 } );
	assert.ok( ! shut.calls.some( ( c ) => c.name === 'fillText' && c.args[ 0 ] === 'nose' ) );

} );
