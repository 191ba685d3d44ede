// The cues' kernels (web/src/core/cues.js): nasal strength from the port's area, the air through
// the tract and its turbulence from the constriction's, the glottis's and the port's areas, the
// air's paths, the particle layouts and a closure stopping the flow.
import { test } from 'node:test';
import assert from 'node:assert/strict';

import {
	CLOSURE_WIDTH_MM, EXIT_MM, FRICATIVE_CHANNEL_MM2, GLOTTIS_OPEN_MM2, GLOTTIS_VOICED_MM2, GLOTTIS_VOICED_OBSTRUENT_MM2, NASAL_FULL_AREA_MM2,
	NASAL_PASSAGE, REFERENCE_FLOW_CM3S, STOP_MARGIN_MM, TURBULENCE_FLOOR_DB, arcLengthAt, areaFromWidth, constrictionAirflow, constrictionAreaFor,
	createPath, glottisAreaFor, hash01, layoutFlow, layoutRings, layoutSwirl, nasalPath, nasalStrength, oralPath, pointAlong,
	tractFlows, turbulenceLevelDb, turbulenceStrength,
} from '../../web/src/core/cues.js';
import { fewestGarbageCollections } from './support/garbage.js';

const TOLERANCE = 1e-9;

// A tract midline from the lips (40, 0) back along the palate and down the pharynx to the larynx.
const MIDLINE = Float64Array.of( 40, 0, 20, 5, 0, 10, - 30, 8, - 50, 0, - 52, - 20, - 50, - 50 );
const GLOTTIS = [ - 40, - 60 ];
const PORT = [ - 58, - 5 ];

test( 'a raised velum (no port) gives no nasal flow; it grows with the area up to full strength', () => {

	assert.equal( nasalStrength( 0 ), 0 );
	assert.equal( nasalStrength( - 1 ), 0 );
	assert.equal( nasalStrength( NaN ), 0 );
	assert.ok( Math.abs( nasalStrength( 28.232 ) - 0.28232 ) < TOLERANCE );
	assert.ok( nasalStrength( 56.5 ) > nasalStrength( 28.2 ) );
	assert.equal( nasalStrength( NASAL_FULL_AREA_MM2 ), 1 );
	assert.equal( nasalStrength( 101.95 ), 1 );

} );

test( 'the area grows with the width as A = 1.5 d^1.5 (cm), and a closure has none', () => {

	assert.ok( Math.abs( areaFromWidth( 10 ) - 150 ) < 1e-9, '1 cm wide: 1.5 cm²' );
	assert.ok( Math.abs( areaFromWidth( 2.73 ) - 21.4 ) < 0.05 );
	for ( const closed of [ 0, CLOSURE_WIDTH_MM, - 1, NaN ] ) assert.equal( areaFromWidth( closed ), 0, String( closed ) );
	assert.equal( areaFromWidth( Infinity ), Infinity );

} );

test( 'the flow through the glottis and the tract follows Bernoulli orifices in series, split by area', () => {

	const flows = {};
	// One orifice of 10 mm² behind a glottis so wide that it costs nothing: U = A sqrt(2 P / rho).
	tractFlows( 1e9, 10, 0, flows );
	assert.ok( Math.abs( flows.total - 10 * Math.sqrt( 2 * 800 / 1.14 ) ) < 1e-6 );
	// The reference /s/: a 10 mm² groove behind an open glottis, about 335 cm³/s (Stevens: 300 to 500).
	assert.ok( REFERENCE_FLOW_CM3S > 300 && REFERENCE_FLOW_CM3S < 400, String( REFERENCE_FLOW_CM3S ) );
	// The mouth and the nose share the air as their areas.
	tractFlows( GLOTTIS_VOICED_MM2, 30, 90, flows );
	assert.ok( Math.abs( flows.oral / flows.total - 0.25 ) < 1e-12 && Math.abs( flows.oral + flows.nasal - flows.total ) < 1e-9 );
	// Nothing flows through a closed glottis or a sealed tract.
	assert.equal( tractFlows( 0, 30, 0, flows ).total, 0 );
	assert.equal( tractFlows( GLOTTIS_OPEN_MM2, 0, 0, flows ).total, 0 );

} );

test( 'the glottis is open for voiceless sounds, half open for voiced obstruents, as in a vowel otherwise', () => {

	assert.equal( glottisAreaFor( { voiced: false, manner: 'fricative' } ), GLOTTIS_OPEN_MM2 );
	assert.equal( glottisAreaFor( { voiced: false, manner: 'stop' } ), GLOTTIS_OPEN_MM2 );
	assert.equal( glottisAreaFor( { voiced: true, manner: 'fricative' } ), GLOTTIS_VOICED_OBSTRUENT_MM2 );
	assert.equal( glottisAreaFor( { voiced: true, manner: 'nasal' } ), GLOTTIS_VOICED_MM2 );
	assert.equal( glottisAreaFor( { voiced: true, manner: 'open' } ), GLOTTIS_VOICED_MM2 );
	assert.equal( glottisAreaFor( null ), GLOTTIS_VOICED_MM2 );

} );

test( 'the noise is 0 dB for the reference /s/, falls with the flow and rises as the same flow narrows', () => {

	assert.ok( Math.abs( turbulenceLevelDb( REFERENCE_FLOW_CM3S, 10 ) ) < 1e-9 );
	assert.ok( Math.abs( turbulenceLevelDb( REFERENCE_FLOW_CM3S / 2, 10 ) - 20 * 3 * Math.log10( 0.5 ) ) < 1e-9 );
	assert.ok( turbulenceLevelDb( 100, 5 ) > turbulenceLevelDb( 100, 10 ) );
	assert.equal( turbulenceLevelDb( 0, 10 ), - Infinity );
	assert.equal( turbulenceLevelDb( 100, 0 ), - Infinity );
	assert.equal( turbulenceStrength( TURBULENCE_FLOOR_DB ), 0 );
	assert.equal( turbulenceStrength( - Infinity ), 0 );
	assert.equal( turbulenceStrength( NaN ), 0 );
	assert.ok( turbulenceStrength( TURBULENCE_FLOOR_DB + 1 ) > 0.35 );
	assert.equal( turbulenceStrength( 0 ), 1 );
	assert.equal( turbulenceStrength( 12 ), 1 );

} );

test( 'the manner says what the width cannot: stops and nasals are closed, fricatives keep a channel', () => {

	assert.equal( constrictionAreaFor( 0.97, 'stop' ), 0 );
	assert.equal( constrictionAreaFor( 0.97, 'nasal' ), 0 );
	assert.equal( constrictionAreaFor( 0, 'fricative' ), FRICATIVE_CHANNEL_MM2 );
	assert.equal( constrictionAreaFor( 0.02, 'affricate' ), FRICATIVE_CHANNEL_MM2 );
	assert.equal( constrictionAreaFor( 2.73, 'fricative' ), areaFromWidth( 2.73 ) );
	assert.equal( constrictionAreaFor( 0.97, null ), areaFromWidth( 0.97 ) );
	assert.equal( constrictionAreaFor( 4, 'close' ), areaFromWidth( 4 ) );

} );

test( 'fricatives hiss and vowels, nasals and closures do not', () => {

	const air = {};
	const at = ( width, port, sound ) => ( { ...constrictionAirflow( width, port, sound, air ) } );
	// /s/ at its 2.73 mm groove, voiceless: loud. /z/, the same groove with the folds vibrating: softer, still heard.
	const s = at( 2.73, 0, { voiced: false, manner: 'fricative' } ), z = at( 2.73, 0, { voiced: true, manner: 'fricative' } );
	assert.ok( s.turbulence > 0.8 && s.passes && s.glottisMm2 === GLOTTIS_OPEN_MM2, JSON.stringify( s ) );
	assert.ok( z.turbulence > 0 && z.levelDb < s.levelDb - 6, JSON.stringify( z ) );
	// /ʃ/ whose section touches at the midline still hisses through its channel.
	assert.ok( at( 0, 0, { voiced: false, manner: 'fricative' } ).turbulence > 0.5 );
	// An open vowel and a close one (4 mm): air flows out of the lips, no hiss.
	for ( const width of [ 10, 4 ] ) {

		const vowel = at( width, 0, { voiced: true, manner: 'close' } );
		assert.ok( vowel.passes && vowel.turbulence === 0 && vowel.oral > 100, JSON.stringify( vowel ) );

	}

	// Lips 0.78 mm apart beside the open port, with no phoneme named: the air leaves by the nose.
	const lips = at( 0.78, 90, null );
	assert.ok( ! lips.passes && lips.turbulence === 0 && lips.nasal > 0.9 * lips.total, JSON.stringify( lips ) );
	// The same lips with the port shut: a bilabial fricative, it hisses.
	assert.ok( at( 0.78, 0, null ).turbulence > 0 );
	// /m/ and /t/, whatever gap the section keeps: closed, so the air goes out of the nose or not at all.
	const m = at( 0.78, 90, { voiced: true, manner: 'nasal' } ), t = at( 0.97, 0, { voiced: false, manner: 'stop' } );
	assert.ok( ! m.passes && m.oral === 0 && m.nasal > 100 && m.turbulence === 0, JSON.stringify( m ) );
	assert.ok( ! t.passes && t.total === 0 && t.turbulence === 0, JSON.stringify( t ) );

} );

test( 'a point along an L-shaped path is found by arc length, with its tangent, clamped at the ends', () => {

	const path = createPath( [ 0, 0, 10, 0, 10, 5 ] );
	assert.equal( path.total, 15 );
	const target = new Float64Array( 4 );
	assert.deepEqual( Array.from( pointAlong( path, 4, target ) ), [ 4, 0, 1, 0 ] );
	assert.deepEqual( Array.from( pointAlong( path, 12, target ) ), [ 10, 2, 0, 1 ] );
	assert.deepEqual( Array.from( pointAlong( path, - 3, target ) ), [ 0, 0, 1, 0 ] );
	assert.deepEqual( Array.from( pointAlong( path, 99, target ) ), [ 10, 5, 0, 1 ] );
	assert.throws( () => createPath( [ 1, 2 ] ), RangeError );

} );

test( 'the oral path runs from the glottis up the tract and out beyond the lips', () => {

	const path = oralPath( MIDLINE, GLOTTIS );
	const p = path.points;
	assert.deepEqual( [ p[ 0 ], p[ 1 ] ], GLOTTIS );
	assert.deepEqual( [ p[ 2 ], p[ 3 ] ], [ - 50, - 50 ], 'then the midline from the larynx' );
	const n = p.length / 2;
	assert.deepEqual( [ p[ 2 * n - 4 ], p[ 2 * n - 3 ] ], [ 40, 0 ], 'through the lips' );
	const exit = Math.hypot( p[ 2 * n - 2 ] - 40, p[ 2 * n - 1 ] );
	assert.ok( Math.abs( exit - EXIT_MM ) < TOLERANCE );
	assert.ok( p[ 2 * n - 2 ] > 40, 'and out in front of them' );

} );

test( 'the nasal path goes up the pharynx, through the port and out of the nose, not into the mouth', () => {

	const path = nasalPath( MIDLINE, GLOTTIS, PORT );
	const p = Array.from( path.points );
	assert.deepEqual( p.slice( 0, 2 ), GLOTTIS );
	const port = p.findIndex( ( v, k ) => k % 2 === 0 && v === PORT[ 0 ] && p[ k + 1 ] === PORT[ 1 ] );
	assert.ok( port > 0, 'passes through the port' );
	for ( let k = 0; k < port; k += 2 ) assert.ok( p[ k + 1 ] <= PORT[ 1 ], `point ${ k / 2 } stays below the port` );
	assert.deepEqual( p.slice( port + 2, port + 2 + NASAL_PASSAGE.length ), NASAL_PASSAGE );
	assert.ok( p[ p.length - 2 ] > NASAL_PASSAGE.at( - 2 ), 'out in front of the nostrils' );

} );

test( 'flow particles lie on their path within the spread, head bright and trails fading', () => {

	const path = createPath( [ 0, 0, 100, 0 ] );
	const count = 10, trail = 4;
	const positions = new Float32Array( 3 * count * trail );
	const colors = new Float32Array( 4 * count * trail );
	const dots = layoutFlow( path, { count, trail, time: 0.3, speed: 50, spacingMm: 2, spreadMm: 1.5 }, positions, colors, 0, 4, 3 );
	assert.equal( dots, count * trail );
	for ( let d = 0; d < dots; d ++ ) {

		assert.ok( positions[ 3 * d ] >= 0 && positions[ 3 * d ] <= 100 );
		assert.ok( Math.abs( positions[ 3 * d + 1 ] ) <= 1.5 + 1e-6, 'within the spread across the path' );
		assert.equal( positions[ 3 * d + 2 ], 0, 'in the mid-sagittal plane' );
		const alpha = colors[ 4 * d + 3 ];
		assert.ok( alpha >= 0 && alpha <= 1 );
		if ( d % trail ) assert.ok( alpha <= colors[ 4 * ( d - d % trail ) + 3 ] + 1e-6, 'a trail dot is no brighter than its head' );

	}

	// Particle 0 moved speed * time along the path (its head, 15 mm from the start, is inside).
	assert.ok( Math.abs( positions[ 0 ] - 15 ) < 1e-4 );

} );

test( 'the arc length of a point is that of its nearest point on the path', () => {

	const path = createPath( [ 0, 0, 10, 0, 10, 5 ] );
	assert.equal( arcLengthAt( path, 4, 1 ), 4 );
	assert.equal( arcLengthAt( path, 12, 3 ), 13 );
	assert.equal( arcLengthAt( path, - 5, 0 ), 0 );
	assert.equal( arcLengthAt( path, 10, 9 ), 15 );

} );

/** The visible dots of the oral flow at `time` (x y alpha each), with the layout's options. */
function oralDots( time, stopMm ) {

	const path = oralPath( MIDLINE, GLOTTIS );
	const count = 30, trail = 6;
	const positions = new Float32Array( 3 * count * trail ), colors = new Float32Array( 4 * count * trail );
	const options = { count, trail, time, speed: 70, spacingMm: 2.4, spreadMm: 2.4, stopMm };
	layoutFlow( path, options, positions, colors, 0, 4, 3 );
	const dots = [];
	for ( let d = 0; d < count * trail; d ++ ) if ( colors[ 4 * d + 3 ] > 0 ) dots.push( [ positions[ 3 * d ], positions[ 3 * d + 1 ], colors[ 4 * d + 3 ] ] );
	return { path, dots, options };

}

test( 'a closure stops the oral flow: the dots gather behind it and none passes, at any time', () => {

	// The tongue tip against the palate at (20, 5), on the way from the palate to the lips (40, 0).
	const path = oralPath( MIDLINE, GLOTTIS );
	const stop = arcLengthAt( path, 20, 5 );
	let free = - Infinity, near = 0, all = 0, openNear = 0, openAll = 0;
	const behind = ( [ x, y ] ) => {

		const s = arcLengthAt( path, x, y );
		return s > stop - 20 && s <= stop;

	};

	for ( let k = 0; k < 120; k ++ ) {

		const time = k / 17;
		const open = oralDots( time, Infinity );
		free = Math.max( free, ...open.dots.map( ( [ x ] ) => x ) );
		openNear += open.dots.filter( behind ).length;
		openAll += open.dots.length;
		const { dots, options } = oralDots( time, stop );
		assert.ok( dots.length > 0, 'the air still comes up to the closure' );
		assert.ok( options.reachMm <= stop - STOP_MARGIN_MM + 1e-9, `a dot at ${ options.reachMm } mm along the path, the closure at ${ stop }` );
		for ( const [ x ] of dots ) assert.ok( x < 20, `a dot at x = ${ x } is past the closure at x = 20 (time ${ time })` );
		near += dots.filter( behind ).length;
		all += dots.length;

	}

	assert.ok( free > 40, 'without the closure the air goes out past the lips' );
	// They gather: the last 20 mm before the closure hold twice the share of the dots they hold in an open flow.
	assert.ok( near / all > 2 * openNear / openAll, `${ near } of ${ all } dots within 20 mm behind the closure; open, ${ openNear } of ${ openAll }` );

} );

test( 'a stop at or past the end of the path leaves the flow as it was', () => {

	const a = oralDots( 0.7, Infinity ), b = oralDots( 0.7, 1e6 );
	assert.deepEqual( a.dots, b.dots );
	assert.ok( a.options.reachMm > a.path.total - EXIT_MM );

} );

test( 'a turbulent swirl stays near the constriction, wider when narrower, and jitters over time', () => {

	const count = 30;
	const a = new Float32Array( 3 * count ), b = new Float32Array( 3 * count ), alphas = new Float32Array( count );
	const extent = ( positions ) => Math.max( ...Array.from( { length: count }, ( _, i ) => Math.hypot( positions[ 3 * i ] - 5, positions[ 3 * i + 1 ] - 7 ) ) );
	layoutSwirl( 5, 7, { count, time: 1, strength: 1, radiusMm: 4 }, a, alphas );
	assert.ok( extent( a ) <= 4 * 1.25 + 1e-6, 'within the radius and its jitter' );
	layoutSwirl( 5, 7, { count, time: 1, strength: 0, radiusMm: 4 }, b, alphas );
	assert.ok( extent( b ) < extent( a ) );
	layoutSwirl( 5, 7, { count, time: 1.05, strength: 1, radiusMm: 4 }, b, alphas );
	assert.notDeepEqual( Array.from( a ), Array.from( b ), 'it moves' );

} );

test( 'voice rings widen from the inner to the outer radius and fade as they grow', () => {

	const rings = layoutRings( 0, 2, 1, 3, 15, new Float64Array( 4 ) );
	assert.deepEqual( Array.from( rings ), [ 3, 0, 9, 0.5 ] );
	const later = layoutRings( 0.25, 2, 1, 3, 15, new Float64Array( 4 ) );
	assert.ok( later[ 0 ] > 3 && later[ 2 ] > 9 && later[ 3 ] < 0.5 );

} );

test( 'the hash is deterministic and in [0, 1)', () => {

	for ( let n = - 50; n < 50; n ++ ) {

		const value = hash01( n );
		assert.equal( value, hash01( n ) );
		assert.ok( value >= 0 && value < 1 );

	}

} );

test( 'the per-frame layouts allocate nothing', async () => {

	const path = oralPath( MIDLINE, GLOTTIS );
	const positions = new Float32Array( 3 * 200 ), colors = new Float32Array( 4 * 200 ), rings = new Float64Array( 6 );
	// The options are made once and updated, as scene/CueLayer.js does.
	const flow = { count: 30, trail: 6, time: 0, speed: 70, spacingMm: 1.8, spreadMm: 2, stopMm: Infinity, reachMm: 0 };
	const swirl = { count: 40, time: 0, strength: 0.8, radiusMm: 5 };
	const air = { glottisMm2: 0, areaMm2: 0, total: 0, oral: 0, nasal: 0, levelDb: 0, turbulence: 0, passes: true };
	const sound = { voiced: false, manner: 'fricative' };
	assert.equal( await fewestGarbageCollections( () => {

		for ( let k = 0; k < 20000; k ++ ) {

			flow.time = swirl.time = k / 60;
			flow.stopMm = k % 2 ? Infinity : 120; // open, then closed at 120 mm along the path
			layoutFlow( path, flow, positions, colors, 0, 4, 3 );
			layoutSwirl( 0, 0, swirl, positions, colors, 0, 4, 3 );
			layoutRings( k / 60, 3, 0.75, 3, 15, rings );
			constrictionAirflow( ( k % 50 ) / 10, k % 3 ? 0 : 90, k % 2 ? sound : null, air );

		}

	} ), 0 );

} );
