// The cues a child can see, as pure numbers: the strength of the nasal flow from the nasal
// port's area; the air through the tract and the turbulence it makes at the narrowest
// constriction, from the constriction's area, the glottis's and the nasal port's (aerodynamics
// below); the paths the air takes in the mid-sagittal plane (from the glottis along the tract's
// midline out of the lips; up the pharynx, through the nasal port and out of the nose) and where
// each particle, trail dot and swirl dot stands at a time. Paths are built once (allocating); the
// per-frame layouts write into given arrays and allocate nothing. Drawing is scene/CueLayer.js.
//
// Aerodynamics (Stevens 1971, "Airflow and turbulence noise for fricative and stop consonants:
// static considerations", JASA 50; Stevens 1998, Acoustic Phonetics, ch. 2 and 8): the lungs
// push at SUBGLOTTAL_PRESSURE_PA through the glottis and then through the oral constriction and
// the nasal port side by side; each narrowing is an orifice whose pressure drop is
// rho U^2 / (2 A^2). The turbulence noise made at the oral constriction grows as U^3 A^-2.5; it is
// given in dB against a voiceless /s/ (a 0.1 cm^2 groove behind an open glottis). The
// constriction's area comes from its mid-sagittal width by the power law A = alpha d^beta of
// area-function studies (Heinz and Stevens 1964; Soquet et al. 2002 compare the published
// coefficients, about 1.3 to 2 for alpha and 1.2 to 1.6 for beta in the oral cavity).
//
// The sound's manner says what the constriction is, where the drawn section cannot: a stop or a
// nasal holds a closure (the rig does not press tissue together, so its section may keep a gap
// of a millimetre), and a fricative's channel is never shut (where the section shows contact the
// air finds the gaps between the teeth and beside the midline), at least FRICATIVE_CHANNEL_MM2.

/** Nasal port area (mm²) of a full-strength nasal flow: the fully lowered velum's port, 102 mm². */
export const NASAL_FULL_AREA_MM2 = 100;
/** The lungs' pressure below the glottis in speech at a comfortable level: 8 cm H2O, in Pa. */
export const SUBGLOTTAL_PRESSURE_PA = 800;
/** Density of the warm, moist air in the tract, kg/m³. */
export const AIR_DENSITY = 1.14;
/** The glottis's mean area (mm²) while the folds vibrate, and held open for a voiceless sound. */
export const GLOTTIS_VOICED_MM2 = 5;
export const GLOTTIS_OPEN_MM2 = 20;
/** A voiced stop or fricative keeps the folds vibrating with the glottis half open, mm². */
export const GLOTTIS_VOICED_OBSTRUENT_MM2 = 10;
/** A = alpha d^beta, A in cm² and d in cm: the oral cavity's law (see above). */
export const AREA_ALPHA = 1.5;
export const AREA_BETA = 1.5;
/** The narrowest channel of a fricative, mm² (0.05 cm², the narrow end of Stevens's fricatives). */
export const FRICATIVE_CHANNEL_MM2 = 5;
/** The reference of the noise level: a voiceless /s/'s groove, mm². */
export const REFERENCE_GROOVE_MM2 = 10;
/** Turbulence noise this many dB under the reference /s/ or less is not shown. */
export const TURBULENCE_FLOOR_DB = - 30;
/** The oral flow passes the constriction when it carries at least this share of the air. */
export const ORAL_PASS_SHARE = 0.1;
/** How far the oral path goes on beyond the lips, and the nasal one beyond the nostrils (mm). */
export const EXIT_MM = 22;
/** A constriction this narrow (mm) or narrower is a closure: what the diagram shows as 0.0 mm. */
export const CLOSURE_WIDTH_MM = 0.05;
/** The oral flow's dots stay this far (mm, along the path) behind a closure. */
export const STOP_MARGIN_MM = 3;

/**
 * The nose's passage above the palate, after the port (x y, mm, project frame): schematic, as
 * there is no nasal cavity mesh. Up the nasopharynx, forward over the hard palate, out of the
 * nostrils in front of the upper lip.
 */
export const NASAL_PASSAGE = Object.freeze( [ - 56, 20, - 40, 30, - 10, 32, 20, 30, 38, 20 ] );

/** 0 for a closed port, rising with its area to 1 at NASAL_FULL_AREA_MM2. */
export function nasalStrength( areaMm2 ) {

	if ( ! ( areaMm2 > 0 ) ) return 0;
	return Math.min( 1, areaMm2 / NASAL_FULL_AREA_MM2 );

}

const OBSTRUENTS = new Set( [ 'stop', 'fricative', 'affricate' ] );
const CLOSURES = new Set( [ 'stop', 'nasal' ] );
const CHANNELS = new Set( [ 'fricative', 'affricate' ] );

/**
 * The glottis's area (mm²) for a phoneme's features ({ voiced, manner }, as GET /phonemes gives
 * them): open for a voiceless sound, half open for a voiced obstruent, as in voicing otherwise
 * (and with no phoneme).
 */
export function glottisAreaFor( features ) {

	if ( ! features ) return GLOTTIS_VOICED_MM2;
	if ( features.voiced === false ) return GLOTTIS_OPEN_MM2;
	return OBSTRUENTS.has( features.manner ) ? GLOTTIS_VOICED_OBSTRUENT_MM2 : GLOTTIS_VOICED_MM2;

}

/** The cross-section area (mm²) of a constriction of mid-sagittal width widthMm (0 when closed). */
export function areaFromWidth( widthMm ) {

	if ( ! ( widthMm > CLOSURE_WIDTH_MM ) ) return 0;
	return 100 * AREA_ALPHA * Math.pow( widthMm / 10, AREA_BETA );

}

/**
 * The oral constriction's area (mm²) for a sound of manner `manner` (null: none, as on the
 * workbench's sliders) at mid-sagittal width widthMm: closed for a stop or a nasal, at least
 * FRICATIVE_CHANNEL_MM2 for a fricative or an affricate's release, from the width otherwise.
 */
export function constrictionAreaFor( widthMm, manner ) {

	if ( CLOSURES.has( manner ) ) return 0;
	const area = areaFromWidth( widthMm );
	return CHANNELS.has( manner ) ? Math.max( FRICATIVE_CHANNEL_MM2, area ) : area;

}

/**
 * The air through the tract (cm³/s) from the glottis's, the oral constriction's and the nasal
 * port's areas (mm²), at SUBGLOTTAL_PRESSURE_PA: the glottis in series with the mouth and the
 * nose, which share the pressure left after it, so that the flow divides as their areas. Writes
 * total, oral and nasal into target and returns it; allocates nothing.
 */
export function tractFlows( glottisMm2, oralMm2, nasalMm2, target ) {

	const outlet = Math.max( 0, oralMm2 ) + Math.max( 0, nasalMm2 );
	const glottis = Math.max( 0, glottisMm2 );
	let total = 0;
	if ( outlet > 0 && glottis > 0 ) {

		// Orifices in series: 1 / A_eff² = 1 / A_glottis² + 1 / A_outlet²; the air crosses A_eff
		// at the speed the whole pressure drop gives. mm² times m/s is cm³/s.
		const effectiveMm2 = 1 / Math.sqrt( 1 / ( glottis * glottis ) + 1 / ( outlet * outlet ) );
		total = effectiveMm2 * Math.sqrt( 2 * SUBGLOTTAL_PRESSURE_PA / AIR_DENSITY );

	}

	target.total = total;
	target.oral = outlet > 0 ? total * Math.max( 0, oralMm2 ) / outlet : 0;
	target.nasal = total - target.oral;
	return target;

}

/** The reference /s/'s flow, cm³/s (about 335). */
export const REFERENCE_FLOW_CM3S = tractFlows( GLOTTIS_OPEN_MM2, REFERENCE_GROOVE_MM2, 0, {} ).oral;

/**
 * The level (dB) of the turbulence noise a flow of U cm³/s makes through an area of A mm²,
 * against the reference voiceless /s/ (U³ A^-2.5; -Infinity without flow).
 */
export function turbulenceLevelDb( flowCm3s, areaMm2 ) {

	if ( ! ( flowCm3s > 0 && areaMm2 > 0 ) ) return - Infinity;
	return 20 * ( 3 * Math.log10( flowCm3s / REFERENCE_FLOW_CM3S ) - 2.5 * Math.log10( areaMm2 / REFERENCE_GROOVE_MM2 ) );

}

/** 0 at or below TURBULENCE_FLOOR_DB; from 0.35 up to 1 as the noise rises to the reference /s/. */
export function turbulenceStrength( levelDb ) {

	if ( ! ( levelDb > TURBULENCE_FLOOR_DB ) ) return 0;
	return 0.35 + 0.65 * Math.min( 1, ( levelDb - TURBULENCE_FLOOR_DB ) / - TURBULENCE_FLOOR_DB );

}

/**
 * What the air does at a constriction of mid-sagittal width widthMm, with the nasal port open
 * portMm2, for a sound with the phoneme features `sound` ({ voiced, manner }, or null for none):
 * writes into target the glottisMm2 and areaMm2 used, the flows (total, oral, nasal, cm³/s),
 * levelDb (the turbulence noise against the reference /s/), turbulence (the strength shown, 0 for
 * none) and passes (whether the oral flow gets past the constriction: it is closed, or so much
 * narrower than the open port that the air goes out of the nose). Returns target; allocates
 * nothing.
 */
export function constrictionAirflow( widthMm, portMm2, sound, target ) {

	const glottis = glottisAreaFor( sound );
	const area = constrictionAreaFor( widthMm, sound?.manner ?? null );
	tractFlows( glottis, area, portMm2, target );
	target.glottisMm2 = glottis;
	target.areaMm2 = area;
	target.passes = target.total > 0 && target.oral >= ORAL_PASS_SHARE * target.total;
	target.levelDb = target.passes ? turbulenceLevelDb( target.oral, area ) : - Infinity;
	target.turbulence = turbulenceStrength( target.levelDb );
	return target;

}

/** A deterministic number in [0, 1) for an integer (a hash: the same on every machine). */
export function hash01( n ) {

	let h = Math.imul( n | 0, 0x9e3779b1 ) ^ 0x85ebca6b;
	h = Math.imul( h ^ ( h >>> 15 ), 0x2c1b3c6d );
	h = Math.imul( h ^ ( h >>> 12 ), 0x297a2d39 );
	return ( ( h ^ ( h >>> 15 ) ) >>> 0 ) / 4294967296;

}

/**
 * A polyline with its arc lengths, for sampling by distance. Allocates.
 * @param {ArrayLike<number>} points x y pairs, at least two points
 * @returns {{ points: Float64Array, lengths: Float64Array, total: number }}
 */
export function createPath( points ) {

	if ( points.length < 4 || points.length % 2 ) throw new RangeError( 'a path needs at least two x y points' );
	const copy = Float64Array.from( points );
	const n = copy.length / 2;
	const lengths = new Float64Array( n );
	for ( let k = 1; k < n; k ++ ) lengths[ k ] = lengths[ k - 1 ] + Math.hypot( copy[ 2 * k ] - copy[ 2 * k - 2 ], copy[ 2 * k + 1 ] - copy[ 2 * k - 1 ] );
	return { points: copy, lengths, total: lengths[ n - 1 ] };

}

/**
 * The point at arc length s (clamped to the path) and the unit tangent there, into
 * target[ 0..3 ] as x, y, tx, ty.
 */
export function pointAlong( path, s, target ) {

	const { points, lengths } = path;
	const n = lengths.length;
	const d = Math.min( path.total, Math.max( 0, s ) );
	let lo = 0, hi = n - 1;
	while ( hi - lo > 1 ) {

		const mid = ( lo + hi ) >> 1;
		if ( lengths[ mid ] <= d ) lo = mid;
		else hi = mid;

	}

	const span = lengths[ hi ] - lengths[ lo ];
	const f = span > 0 ? ( d - lengths[ lo ] ) / span : 0;
	const dx = points[ 2 * hi ] - points[ 2 * lo ], dy = points[ 2 * hi + 1 ] - points[ 2 * lo + 1 ];
	const length = Math.sqrt( dx * dx + dy * dy ) || 1; // not Math.hypot, which allocates its arguments
	target[ 0 ] = points[ 2 * lo ] + dx * f;
	target[ 1 ] = points[ 2 * lo + 1 ] + dy * f;
	target[ 2 ] = dx / length;
	target[ 3 ] = dy / length;
	return target;

}

/**
 * The arc length along `path` of its point nearest (x, y): where a closure at (x, y) stops the
 * flow. Allocates nothing.
 */
export function arcLengthAt( path, x, y ) {

	const { points, lengths } = path;
	let best = Infinity, at = 0;
	for ( let k = 0; k + 1 < lengths.length; k ++ ) {

		const ax = points[ 2 * k ], ay = points[ 2 * k + 1 ];
		const dx = points[ 2 * k + 2 ] - ax, dy = points[ 2 * k + 3 ] - ay;
		const span2 = dx * dx + dy * dy;
		const f = span2 > 0 ? Math.min( 1, Math.max( 0, ( ( x - ax ) * dx + ( y - ay ) * dy ) / span2 ) ) : 0;
		const ex = ax + f * dx - x, ey = ay + f * dy - y;
		const d2 = ex * ex + ey * ey;
		if ( d2 < best ) {

			best = d2;
			at = lengths[ k ] + f * ( lengths[ k + 1 ] - lengths[ k ] );

		}

	}

	return at;

}

/**
 * The oral path: from the glottis, along the tract's midline from the larynx to the lips, and
 * EXIT_MM on beyond the lips. Allocates.
 * @param {Float64Array} midline x y per sample from the lips to the larynx (tractMidline)
 * @param {ArrayLike<number>} glottis x y (mm)
 */
export function oralPath( midline, glottis ) {

	const n = midline.length / 2;
	const points = [ glottis[ 0 ], glottis[ 1 ] ];
	for ( let k = n - 1; k >= 0; k -- ) points.push( midline[ 2 * k ], midline[ 2 * k + 1 ] );
	const dx = midline[ 0 ] - midline[ 2 ], dy = midline[ 1 ] - midline[ 3 ];
	const length = Math.hypot( dx, dy ) || 1;
	points.push( midline[ 0 ] + EXIT_MM * dx / length, midline[ 1 ] + EXIT_MM * dy / length );
	return createPath( points );

}

/**
 * The nasal path: from the glottis up the midline's pharyngeal part (the samples behind and below
 * the port), through the nasal port, along NASAL_PASSAGE and EXIT_MM out of the nostrils. Allocates.
 * @param {Float64Array} midline x y per sample from the lips to the larynx (tractMidline)
 * @param {ArrayLike<number>} glottis x y (mm)
 * @param {ArrayLike<number>} port x y of the nasal port (mm)
 */
export function nasalPath( midline, glottis, port ) {

	const points = [ glottis[ 0 ], glottis[ 1 ] ];
	for ( let k = midline.length / 2 - 1; k >= 0; k -- ) {

		const x = midline[ 2 * k ], y = midline[ 2 * k + 1 ];
		if ( y > port[ 1 ] - 4 ) break; // the midline turns forward into the mouth here
		points.push( x, y );

	}

	points.push( port[ 0 ], port[ 1 ], ...NASAL_PASSAGE );
	const m = NASAL_PASSAGE.length;
	const dx = NASAL_PASSAGE[ m - 2 ] - NASAL_PASSAGE[ m - 4 ], dy = NASAL_PASSAGE[ m - 1 ] - NASAL_PASSAGE[ m - 3 ];
	const length = Math.hypot( dx, dy );
	points.push( NASAL_PASSAGE[ m - 2 ] + EXIT_MM * dx / length, NASAL_PASSAGE[ m - 1 ] + EXIT_MM * dy / length );
	return createPath( points );

}

/** Fade over the first and last `edgeMm` of a path: 0 at its ends, 1 inside. */
function edgeFade( s, total, edgeMm ) {

	return Math.max( 0, Math.min( 1, s / edgeMm, ( total - s ) / edgeMm ) );

}

const scratch = new Float64Array( 4 );

/**
 * Particles flowing along a path, each with a fading trail: particle i's head is at arc length
 * ( i / count + time * speed / total ) mod 1 of the path, its trail dots `spacingMm` apart behind
 * it, each dot offset across the path by up to ±spreadMm (fixed per particle), so that the air is
 * a stream. Writes count * trail dots: x y z into positions[ 3 * ( first + dot ) ] and an alpha
 * (head 1, fading along the trail and at the path's ends, times `alpha`) into
 * alphas[ alphaStride * ( first + dot ) + alphaOffset ]. Allocates nothing.
 *
 * With `stopMm` short of the path's end (a closure there), the flow is blocked: the particles
 * run on the path up to STOP_MARGIN_MM before stopMm, slowing as they come (eased to a stop), so
 * that they gather behind the closure and fade there, and none passes it.
 * Sets `options.reachMm`, the farthest arc length of a dot drawn (alpha above 0).
 * @returns {number} the dots written
 */
export function layoutFlow( path, options, positions, alphas, first = 0, alphaStride = 1, alphaOffset = 0 ) {

	const { count, trail, time, speed, spacingMm, spreadMm, alpha = 1, seed = 0, stopMm = Infinity } = options;
	const blocked = stopMm < path.total;
	const total = blocked ? Math.max( 0, stopMm - STOP_MARGIN_MM ) : path.total;
	let dot = first;
	let reach = 0;
	for ( let i = 0; i < count; i ++ ) {

		const phase = total > 0 ? i / count + time * speed / total : 0;
		const head = ( phase - Math.floor( phase ) ) * total;
		const across = ( 2 * hash01( seed + i ) - 1 ) * spreadMm;
		for ( let j = 0; j < trail; j ++ ) {

			const u = head - j * spacingMm;
			let s = u, fade;
			if ( blocked ) {

				const left = total > 0 ? Math.max( 0, 1 - u / total ) : 0;
				s = total * ( 1 - left * left );
				fade = Math.max( 0, Math.min( 1, u / 6, 10 * left ) );

			} else fade = edgeFade( s, total, 6 );

			pointAlong( path, s, scratch );
			positions[ 3 * dot ] = scratch[ 0 ] - scratch[ 3 ] * across;
			positions[ 3 * dot + 1 ] = scratch[ 1 ] + scratch[ 2 ] * across;
			positions[ 3 * dot + 2 ] = 0;
			const a = alpha * ( 1 - j / trail ) * fade;
			alphas[ alphaStride * dot + alphaOffset ] = a;
			if ( a > 0 && s > reach ) reach = s;
			dot ++;

		}

	}

	options.reachMm = reach;
	return dot - first;

}

/**
 * A turbulent patch: `count` dots swirling about (cx, cy) on circles of up to radiusMm (times
 * strength, at least a third of it), each jittering anew 30 times a second. Positions and alphas
 * as layoutFlow. Allocates nothing.
 * @returns {number} the dots written
 */
export function layoutSwirl( cx, cy, { count, time, strength, radiusMm, seed = 0 }, positions, alphas, first = 0, alphaStride = 1, alphaOffset = 0 ) {

	const tick = Math.floor( time * 30 );
	for ( let i = 0; i < count; i ++ ) {

		const dot = first + i;
		const r = radiusMm * ( 0.33 + 0.67 * strength ) * ( 0.25 + 0.75 * hash01( seed + i ) );
		const turn = ( hash01( seed + 7919 + i ) < 0.5 ? - 1 : 1 ) * ( 5 + 6 * hash01( seed + 104729 + i ) );
		const angle = 2 * Math.PI * hash01( seed + 31 * i + 3 ) + turn * time;
		const jitter = 0.35 * r;
		positions[ 3 * dot ] = cx + r * Math.cos( angle ) + jitter * ( hash01( seed + tick * 131 + 2 * i ) - 0.5 );
		positions[ 3 * dot + 1 ] = cy + r * Math.sin( angle ) + jitter * ( hash01( seed + tick * 131 + 2 * i + 1 ) - 0.5 );
		positions[ 3 * dot + 2 ] = 0;
		alphas[ alphaStride * dot + alphaOffset ] = 0.55 + 0.45 * hash01( seed + tick * 17 + i );

	}

	return count;

}

/**
 * Expanding rings of the voice's buzz: ring k of `count` grows from innerMm to outerMm over
 * periodS, staggered; writes its radius and alpha (fading as it grows) into target[ 2k ], [ 2k+1 ].
 */
export function layoutRings( time, count, periodS, innerMm, outerMm, target ) {

	for ( let k = 0; k < count; k ++ ) {

		const phase = time / periodS + k / count;
		const f = phase - Math.floor( phase );
		target[ 2 * k ] = innerMm + ( outerMm - innerMm ) * f;
		target[ 2 * k + 1 ] = ( 1 - f ) * Math.min( 1, 6 * f );

	}

	return target;

}
