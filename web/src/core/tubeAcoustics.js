// A vocal tract as a lossy tube: the volume-velocity transfer function from the glottis to the
// lips, and its formants. The twin of server/glasshead/acoustics/tube.py (its docstring gives the
// model and its sources), held to the same numbers by tests/vectors/tube-acoustics.json: a chain
// of cylindrical sections (lengths mm, areas mm², glottis first), each a lossy transmission line
// with viscous and thermal losses and yielding walls, a closed glottis driven by a volume
// velocity, and a piston-in-a-baffle load at the lips. Complex numbers are written out as pairs
// of doubles; a call allocates nothing once its grid exists.

import { TUBE_AIR, TUBE_FORMANT_BAND_HZ, TUBE_GRID_STEP_HZ, TUBE_WALL } from './constants.js';

const RHO = TUBE_AIR.density;
const C = TUBE_AIR.sound_speed;
const VISCOUS = RHO * TUBE_AIR.viscosity / 2;
const THERMAL = ( TUBE_AIR.heat_ratio - 1 ) / ( RHO * C * C );
const THERMAL_ROOT = TUBE_AIR.heat_conductivity / ( 2 * TUBE_AIR.specific_heat * RHO );

/** Formants reported by default. */
export const FORMANT_COUNT = 4;

// sqrt of (re, im), principal branch (numpy's): written into S[0], S[1].
const S = new Float64Array( 2 );
function csqrt( re, im ) {

	const r = Math.hypot( re, im );
	const a = Math.sqrt( Math.max( ( r + re ) / 2, 0 ) );
	const b = Math.sqrt( Math.max( ( r - re ) / 2, 0 ) );
	S[ 0 ] = a;
	S[ 1 ] = im < 0 ? - b : b;

}

/** Chain matrices [[a, b], [c, d]], complex, re and im of each: the whole tube (or the part
 * before a nasal junction), the part after the junction, and the nose. */
const K = new Float64Array( 8 );
const AFTER = new Float64Array( 8 );
const NOSE = new Float64Array( 8 );
// What depends on the frequency alone (frequencyTerms): the boundary layers' depth and the walls' admittance.
let viscousRoot = 0, thermalRoot = 0, wallR = 0, wallI = 0;

function frequencyTerms( omega ) {

	viscousRoot = Math.sqrt( omega * VISCOUS );
	thermalRoot = THERMAL * Math.sqrt( THERMAL_ROOT * omega );
	const wr = TUBE_WALL.resistance, wi = omega * TUBE_WALL.mass - TUBE_WALL.stiffness / omega;
	const wn = wr * wr + wi * wi;
	wallR = wr / wn;
	wallI = - wi / wn;

}

/** The chain matrix of sections [from, to) at omega into M (frequencyTerms( omega ) first). */
function chainInto( M, lengths, areas, from, to, omega, lossy ) {

	M.fill( 0 );
	M[ 0 ] = 1;
	M[ 6 ] = 1;
	for ( let k = from; k < to; k ++ ) {

		const area = areas[ k ] * 1e-6;
		const length = lengths[ k ] * 1e-3;
		const perimeter = 2 * Math.sqrt( Math.PI * area );
		let zr = 0, zi = omega * RHO / area; // series impedance per unit length
		let yr = 0, yi = omega * area / ( RHO * C * C ); // shunt admittance per unit length
		if ( lossy ) {

			const viscous = perimeter / ( area * area ) * viscousRoot;
			zr += viscous;
			zi += viscous;
			const thermal = perimeter * thermalRoot;
			// The walls: perimeter / (R + j(ωM - K/ω)).
			yr += thermal + perimeter * wallR;
			yi += thermal + perimeter * wallI;

		}

		// γ = sqrt(z y), Z0 = sqrt(z / y).
		csqrt( zr * yr - zi * yi, zr * yi + zi * yr );
		const gr = S[ 0 ] * length, gi = S[ 1 ] * length;
		const yn = yr * yr + yi * yi;
		csqrt( ( zr * yr + zi * yi ) / yn, ( zi * yr - zr * yi ) / yn );
		const z0r = S[ 0 ], z0i = S[ 1 ];
		const e = Math.exp( gr ), ch = ( e + 1 / e ) / 2, sh = ( e - 1 / e ) / 2;
		const cs = Math.cos( gi ), sn = Math.sin( gi );
		const coshR = ch * cs, coshI = sh * sn; // cosh(γl)
		const sinhR = sh * cs, sinhI = ch * sn; // sinh(γl)
		const br = z0r * sinhR - z0i * sinhI, bi = z0r * sinhI + z0i * sinhR; // Z0 sinh
		const z0n = z0r * z0r + z0i * z0i;
		const cr = ( sinhR * z0r + sinhI * z0i ) / z0n, ci = ( sinhI * z0r - sinhR * z0i ) / z0n; // sinh / Z0
		// M = M · [[cosh, b], [c, cosh]].
		for ( let row = 0; row < 8; row += 4 ) {

			const pr = M[ row ], pi = M[ row + 1 ], qr = M[ row + 2 ], qi = M[ row + 3 ];
			M[ row ] = pr * coshR - pi * coshI + qr * cr - qi * ci;
			M[ row + 1 ] = pr * coshI + pi * coshR + qr * ci + qi * cr;
			M[ row + 2 ] = pr * br - pi * bi + qr * coshR - qi * coshI;
			M[ row + 3 ] = pr * bi + pi * br + qr * coshI + qi * coshR;

		}

	}

}

/** The radiation load of an opening of `areaMm2` at omega, into L (re, im); 0 when lossless. */
const L = new Float64Array( 2 );
function radiation( areaMm2, omega, lossy ) {

	if ( ! lossy ) {

		L[ 0 ] = L[ 1 ] = 0;
		return L;

	}

	// Z_rad = R jωL / (R + jωL).
	const area = areaMm2 * 1e-6;
	const resistance = 128 * RHO * C / ( 9 * Math.PI * Math.PI * area );
	const reactance = omega * 8 * RHO / ( 3 * Math.PI * Math.sqrt( Math.PI * area ) );
	const n = resistance * resistance + reactance * reactance;
	L[ 0 ] = resistance * reactance * reactance / n;
	L[ 1 ] = resistance * resistance * reactance / n;
	return L;

}

/** M's row `row` (0 or 1) against the load: M[row][0] Z + M[row][1], into P (re, im). */
const P = new Float64Array( 8 );
function loaded( M, row, offset ) {

	const i = 4 * row;
	P[ offset ] = M[ i ] * L[ 0 ] - M[ i + 1 ] * L[ 1 ] + M[ i + 2 ];
	P[ offset + 1 ] = M[ i ] * L[ 1 ] + M[ i + 1 ] * L[ 0 ] + M[ i + 3 ];

}

/**
 * U_lips / U_glottis at `frequency` Hz, written into out[0] (re) and out[1] (im); with a nasal
 * branch `nasal` = { at, lengths, areas } (the nose from its port to the nostrils, leaving the
 * tract after its first `at` sections), ( U_lips + U_nose ) / U_glottis, as tube.py derives it.
 * `lossy` false: no losses and ideal open ends (the textbook tube). Areas and lengths must be
 * positive.
 */
export function tubeTransfer( lengths, areas, frequency, lossy = true, out = new Float64Array( 2 ), nasal = null ) {

	const omega = 2 * Math.PI * frequency;
	frequencyTerms( omega );
	const n = lengths.length;
	if ( ! nasal ) {

		// 1 / (K21 Z_rad + K22).
		chainInto( K, lengths, areas, 0, n, omega, lossy );
		radiation( areas[ n - 1 ], omega, lossy );
		loaded( K, 1, 0 );
		const dn = P[ 0 ] * P[ 0 ] + P[ 1 ] * P[ 1 ];
		out[ 0 ] = P[ 0 ] / dn;
		out[ 1 ] = - P[ 1 ] / dn;
		return out;

	}

	const at = nasal.at;
	if ( ! ( at >= 1 && at < n ) ) throw new RangeError( `a nasal branch must leave the tract between two of its sections, not after section ${ at } of ${ n }` );
	chainInto( K, lengths, areas, 0, at, omega, lossy );
	chainInto( AFTER, lengths, areas, at, n, omega, lossy );
	chainInto( NOSE, nasal.lengths, nasal.areas, 0, nasal.lengths.length, omega, lossy );
	radiation( areas[ n - 1 ], omega, lossy );
	loaded( AFTER, 0, 0 ); // a
	loaded( AFTER, 1, 2 ); // b
	radiation( nasal.areas[ nasal.areas.length - 1 ], omega, lossy );
	loaded( NOSE, 0, 4 ); // c
	loaded( NOSE, 1, 6 ); // d
	const [ ar, ai, br, bi, cr, ci, dr, di ] = P;
	// (a + c) / (K21 a c + K22 (b c + a d)).
	const acR = ar * cr - ai * ci, acI = ar * ci + ai * cr;
	const sumR = br * cr - bi * ci + ar * dr - ai * di, sumI = br * ci + bi * cr + ar * di + ai * dr;
	const denR = K[ 4 ] * acR - K[ 5 ] * acI + K[ 6 ] * sumR - K[ 7 ] * sumI;
	const denI = K[ 4 ] * acI + K[ 5 ] * acR + K[ 6 ] * sumI + K[ 7 ] * sumR;
	const numR = ar + cr, numI = ai + ci;
	const dn = denR * denR + denI * denI;
	out[ 0 ] = ( numR * denR + numI * denI ) / dn;
	out[ 1 ] = ( numI * denR - numR * denI ) / dn;
	return out;

}

let grid = null;
let decibels = null;
const H = new Float64Array( 2 );

/**
 * The first `count` formants of the tube (with its nasal branch, if any): out.frequencies and out.bandwidths (Hz), NaN where the
 * band (TUBE_FORMANT_BAND_HZ) holds fewer peaks; peaks found on a TUBE_GRID_STEP_HZ grid and each
 * refined by a parabola through its three dB values; the bandwidth is the peak's width 3 dB down.
 */
export function tubeFormants( lengths, areas, { count = FORMANT_COUNT, lossy = true, nasal = null } = {}, out = { frequencies: new Float64Array( count ), bandwidths: new Float64Array( count ) } ) {

	const step = TUBE_GRID_STEP_HZ;
	if ( grid === null ) {

		const [ low, high ] = TUBE_FORMANT_BAND_HZ;
		const n = Math.floor( ( high - low ) / step + 0.5 ) + 1;
		grid = new Float64Array( n );
		decibels = new Float64Array( n );
		for ( let i = 0; i < n; i ++ ) grid[ i ] = low + i * step;

	}

	for ( let i = 0; i < grid.length; i ++ ) {

		tubeTransfer( lengths, areas, grid[ i ], lossy, H, nasal );
		decibels[ i ] = 20 * Math.log10( Math.hypot( H[ 0 ], H[ 1 ] ) + 1e-300 );

	}

	out.frequencies.fill( Number.NaN );
	out.bandwidths.fill( Number.NaN );
	let slot = 0;
	for ( let i = 1; i < grid.length - 1 && slot < count; i ++ ) {

		const left = decibels[ i - 1 ], centre = decibels[ i ], right = decibels[ i + 1 ];
		if ( ! ( centre > left && centre >= right ) ) continue;
		const curvature = left - 2 * centre + right;
		const offset = curvature < 0 ? 0.5 * ( left - right ) / curvature : 0;
		out.frequencies[ slot ] = grid[ i ] + offset * step;
		out.bandwidths[ slot ] = widthAt( i, centre - 0.25 * ( left - right ) * offset - 3 );
		slot ++;

	}

	return out;

}

/** Width of the peak at grid index `peak` where it falls to `level` dB on each side, or NaN. */
function widthAt( peak, level ) {

	let low = 0, high = 0;
	for ( const direction of [ - 1, 1 ] ) {

		let k = peak;
		while ( k + direction >= 0 && k + direction < decibels.length && decibels[ k + direction ] <= decibels[ k ] && decibels[ k + direction ] > level ) k += direction;
		const next = k + direction;
		if ( next < 0 || next >= decibels.length || decibels[ next ] > level ) return Number.NaN;
		const edge = grid[ k ] + direction * ( decibels[ k ] - level ) / ( decibels[ k ] - decibels[ next ] ) * ( grid[ 1 ] - grid[ 0 ] );
		if ( direction < 0 ) low = edge;
		else high = edge;

	}

	return high - low;

}
