// The listening page's mouth panel without a browser: the drawing of the target's and the
// learner's tongue (web/src/ui/listen/mouthDrawing.js) into a recording 2D context, the tongue's
// mid-sagittal curve for any parameters (tongueProfile.js) on the built rig, and where the panel
// goes beside or under the vowel chart (MouthPanel.js topRowSizes).
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { existsSync, readFileSync } from 'node:fs';

import { drawMouth, MOUTH_COLORS, MOUTH_WORDS } from '../../web/src/ui/listen/mouthDrawing.js';
import { TongueProfile } from '../../web/src/ui/listen/tongueProfile.js';
import { SIDE_BY_SIDE_PX, topRowSizes } from '../../web/src/ui/listen/MouthPanel.js';

/** A 2D context that records its calls with the styles and dash at each. */
function recorder() {

	const calls = [];
	let dash = [];
	return new Proxy( { calls, fillStyle: '', strokeStyle: '', lineWidth: 1 }, {
		get( target, name ) {

			if ( name in target ) return target[ name ];
			if ( name === 'measureText' ) return ( text ) => ( { width: 9 * text.length } );
			if ( name === 'setLineDash' ) return ( segments ) => ( dash = segments );
			return ( ...args ) => calls.push( { name, args, fillStyle: target.fillStyle, strokeStyle: target.strokeStyle, dash } );

		},
		set( target, name, value ) {

			target[ name ] = value;
			return true;

		},
	} );

}

/** A closed curve: a rectangle x0..x0+20, y0..y0+10 (mm), x y per point. */
const box = ( x0, y0 ) => Float64Array.of( x0, y0, x0 + 20, y0, x0 + 20, y0 + 10, x0, y0 + 10 );
const SIZE = { width: 360, height: 320 };
const texts = ( ctx ) => ctx.calls.filter( ( c ) => c.name === 'fillText' ).map( ( c ) => c.args[ 0 ] );

test( 'the target\'s tongue is filled, the learner\'s is a dashed outline of another colour, and the legend names both', () => {

	const ctx = recorder();
	drawMouth( ctx, { target: box( - 30, - 20 ), estimate: box( - 20, - 10 ) }, SIZE );
	const fills = ctx.calls.filter( ( c ) => c.name === 'fill' );
	assert.ok( fills.some( ( c ) => c.fillStyle === MOUTH_COLORS.targetFill ), 'the target is filled' );
	const strokes = ctx.calls.filter( ( c ) => c.name === 'stroke' );
	assert.ok( strokes.some( ( c ) => c.strokeStyle === MOUTH_COLORS.target && c.dash.length === 0 ), 'the target has a solid edge' );
	assert.ok( strokes.some( ( c ) => c.strokeStyle === MOUTH_COLORS.yours && c.dash.length > 0 ), 'the learner\'s tongue is dashed' );
	assert.ok( ! fills.some( ( c ) => c.fillStyle === MOUTH_COLORS.yours ), 'the learner\'s tongue is not filled' );
	assert.notEqual( MOUTH_COLORS.target, MOUTH_COLORS.yours );
	const words = texts( ctx );
	for ( const word of [ MOUTH_WORDS.target, MOUTH_WORDS.yours ] ) assert.ok( words.includes( word ), words.join( ' | ' ) );
	assert.ok( ! words.includes( MOUTH_WORDS.noTarget ) );

} );

test( 'until an attempt is measured only the target shows; without a target the drawing asks for one', () => {

	const targetOnly = recorder();
	drawMouth( targetOnly, { target: box( - 30, - 20 ), estimate: null }, SIZE );
	assert.ok( texts( targetOnly ).includes( MOUTH_WORDS.target ) );
	assert.ok( ! texts( targetOnly ).includes( MOUTH_WORDS.yours ) );
	assert.ok( ! targetOnly.calls.some( ( c ) => c.name === 'stroke' && c.strokeStyle === MOUTH_COLORS.yours ) );
	const none = recorder();
	drawMouth( none, {}, SIZE );
	assert.ok( texts( none ).includes( MOUTH_WORDS.noTarget ) );
	assert.ok( ! texts( none ).includes( MOUTH_WORDS.target ) );

} );

test( 'the drawing keeps anterior on the left, as the head\'s profile beside it', () => {

	const view = drawMouth( recorder(), { target: box( - 30, - 20 ) }, SIZE );
	assert.ok( view.x( 20 ) < view.x( - 40 ), 'the lips (+x) are left of the throat' );
	assert.ok( view.y( 10 ) < view.y( - 10 ), 'up is up' );
	for ( const [ x, y ] of [ [ - 66, - 46 ], [ 34, 30 ] ] ) {

		assert.ok( view.x( x ) >= 0 && view.x( x ) <= SIZE.width && view.y( y ) >= 0 && view.y( y ) <= SIZE.height, `${ x }, ${ y } is on the canvas` );

	}

} );

const BUILD = new URL( '../../assets/build/', import.meta.url );
const built = existsSync( new URL( 'tongue-rig.json', BUILD ) ) && existsSync( new URL( 'phoneme-targets.json', BUILD ) );
const readBuilt = ( name ) => JSON.parse( readFileSync( new URL( name, BUILD ), 'utf8' ) );

test( 'on the built rig, /i/\'s tongue stands higher at the front than /ɑ/\'s, and out-of-range or unknown parameters do not throw', { skip: ! built && 'assets/build is not built' }, () => {

	const profile = new TongueProfile( readBuilt( 'tongue-rig.json' ) );
	const targets = Object.fromEntries( readBuilt( 'phoneme-targets.json' ).targets.map( ( t ) => [ t.arpabet, t.params ] ) );
	const top = ( curve, xMin ) => {

		let y = - Infinity;
		for ( let k = 0; k < curve.length; k += 2 ) if ( curve[ k ] >= xMin ) y = Math.max( y, curve[ k + 1 ] );
		return y;

	};
	const iy = profile.curve( targets.IY );
	const aa = profile.curve( targets.AA );
	assert.equal( iy.length, 2 * profile.rig.stationCount );
	assert.ok( iy.every( Number.isFinite ) && aa.every( Number.isFinite ) );
	const front = - 20; // mm: in front of the soft palate
	assert.ok( top( iy, front ) > top( aa, front ) + 3, `front of the tongue: /i/ ${ top( iy, front ) } mm, /ɑ/ ${ top( aa, front ) } mm` );
	const wild = profile.curve( { ...targets.IY, dorsum_height: 1e6, lip_rounding: 0.5, not_a_parameter: 3 } );
	assert.ok( wild.every( Number.isFinite ) );
	// The same parameters give the same curve, whatever came before (no state kept between calls).
	assert.deepEqual( Array.from( profile.curve( targets.IY ) ), Array.from( iy ) );

} );

test( 'the chart and the mouth sit side by side on a projector and one under the other on a tablet, within the width', () => {

	const wide = topRowSizes( 1570 );
	assert.ok( wide.chart.width + wide.mouth.width + 12 <= 1570 && wide.chart.height === wide.mouth.height );
	const narrow = topRowSizes( 738 );
	assert.equal( narrow.chart.width, 738 );
	assert.equal( narrow.mouth.width, 738 );
	assert.ok( topRowSizes( SIDE_BY_SIDE_PX - 1 ).mouth.width === SIDE_BY_SIDE_PX - 1 );

} );
