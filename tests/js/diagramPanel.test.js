// The diagram panel (web/src/ui/shared/DiagramPanel.js) drawn into a recording 2D context: every part's
// chains are traced, closed loops filled, and the constriction marked with its width and place.
import { test } from 'node:test';
import assert from 'node:assert/strict';

import { createSectionPart, cutSection } from '../../web/src/core/midSection.js';
import { DIAGRAM_COLORS, drawDiagram } from '../../web/src/ui/shared/DiagramPanel.js';

/** A 2D context that records its calls and the fill style at each fill. */
function recorder() {

	const calls = [];
	return new Proxy( { calls, fillStyle: '', strokeStyle: '' }, {
		get( target, name ) {

			if ( name in target ) return target[ name ];
			if ( name === 'measureText' ) return ( text ) => ( { width: 7 * text.length } );
			return ( ...args ) => calls.push( { name, args, fillStyle: target.fillStyle, strokeStyle: target.strokeStyle } );

		},
		set( target, name, value ) {

			target[ name ] = value;
			return true;

		},
	} );

}

/** The section of a box [ x0, x0 + 4 ] x [ 0, 2 ] x [ -1, 1 ]. */
function boxSection( x0 ) {

	const positions = new Float32Array( 24 );
	for ( let v = 0; v < 8; v ++ ) positions.set( [ x0 + ( v & 1 ? 4 : 0 ), v & 2 ? 2 : 0, v & 4 ? 1 : - 1 ], 3 * v );
	const quads = [ [ 0, 1, 3, 2 ], [ 4, 6, 7, 5 ], [ 0, 4, 5, 1 ], [ 2, 3, 7, 6 ], [ 0, 2, 6, 4 ], [ 1, 5, 7, 3 ] ];
	const part = createSectionPart( Uint32Array.from( quads.flatMap( ( [ a, b, c, d ] ) => [ a, b, c, a, c, d ] ) ), 8 );
	cutSection( part, positions );
	return part;

}

test( 'the diagram fills the tongue\'s loop in the tongue colour, traces every point, and marks the constriction with its label', () => {

	const ctx = recorder();
	const tongue = boxSection( 0 );
	const palate = boxSection( 10 );
	drawDiagram( ctx, {
		parts: { tongue: [ tongue ], palate: [ palate ] },
		air: { outline: Float64Array.of( - 5, - 5, 20, - 5, 20, 5 ), holes: [] },
		constriction: { widthMm: 1.25, place: 'alveolar', floor: [ 4, 1 ], roof: [ 10, 1 ] },
	}, { width: 300, height: 200 } );
	const fills = ctx.calls.filter( ( c ) => c.name === 'fill' ).map( ( c ) => c.fillStyle );
	assert.ok( fills.includes( DIAGRAM_COLORS.air ) );
	assert.ok( fills.includes( DIAGRAM_COLORS.tongue ) );
	assert.ok( fills.includes( DIAGRAM_COLORS.bone ) );
	// Each box's 8 points are traced twice (fill and stroke): 2 moveTo + 14 lineTo per box.
	assert.equal( ctx.calls.filter( ( c ) => c.name === 'lineTo' ).length >= 2 * 2 * 7, true );
	const texts = ctx.calls.filter( ( c ) => c.name === 'fillText' ).map( ( c ) => c.args[ 0 ] );
	assert.ok( texts.includes( '1.3 mm · alveolar' ), texts.join( ' | ' ) );
	assert.ok( ctx.calls.some( ( c ) => c.name === 'stroke' && c.strokeStyle === DIAGRAM_COLORS.constriction ) );

} );

test( 'the label stays inside the panel when the gap is at its edge', () => {

	const ctx = recorder();
	drawDiagram( ctx, { parts: {}, constriction: { widthMm: 2, place: 'bilabial', floor: [ 50, 0 ], roof: [ 50, 1 ] } }, { width: 300, height: 200 } );
	const label = ctx.calls.find( ( c ) => c.name === 'fillText' && c.args[ 0 ].startsWith( '2.0 mm' ) );
	const half = 7 * label.args[ 0 ].length / 2;
	assert.ok( label.args[ 1 ] - half >= 0 && label.args[ 1 ] + half <= 300, `label at x = ${ label.args[ 1 ] }` );

} );
