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

/** The running chain matrix [[a, b], [c, d]], complex: re and im of each. */
const K = new Float64Array( 8 );

/**
 * U_lips / U_glottis at `frequency` Hz, written into out[0] (re) and out[1] (im). `lossy` false:
 * no losses and an ideal open end (the textbook tube). Areas and lengths must be positive.
 */
export function tubeTransfer( lengths, areas, frequency, lossy = true, out = new Float64Array( 2 ) ) {

	const omega = 2 * Math.PI * frequency;
	// What depends on the frequency alone: the boundary layers' depth and the walls' admittance.
	const viscousRoot = Math.sqrt( omega * VISCOUS );
	const thermalRoot = THERMAL * Math.sqrt( THERMAL_ROOT * omega );
	const wr = TUBE_WALL.resistance, wi = omega * TUBE_WALL.mass - TUBE_WALL.stiffness / omega;
	const wn = wr * wr + wi * wi;
	const wallR = wr / wn, wallI = - wi / wn;
	K.fill( 0 );
	K[ 0 ] = 1;
	K[ 6 ] = 1;
	for ( let k = 0; k < lengths.length; k ++ ) {

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
		// K = K · [[cosh, b], [c, cosh]].
		for ( let row = 0; row < 8; row += 4 ) {

			const pr = K[ row ], pi = K[ row + 1 ], qr = K[ row + 2 ], qi = K[ row + 3 ];
			K[ row ] = pr * coshR - pi * coshI + qr * cr - qi * ci;
			K[ row + 1 ] = pr * coshI + pi * coshR + qr * ci + qi * cr;
			K[ row + 2 ] = pr * br - pi * bi + qr * coshR - qi * coshI;
			K[ row + 3 ] = pr * bi + pi * br + qr * coshI + qi * coshR;

		}

	}

	// 1 / (K21 Z_rad + K22), Z_rad = R jωL / (R + jωL).
	let dr = K[ 6 ], di = K[ 7 ];
	if ( lossy ) {

		const area = areas[ areas.length - 1 ] * 1e-6;
		const resistance = 128 * RHO * C / ( 9 * Math.PI * Math.PI * area );
		const reactance = omega * 8 * RHO / ( 3 * Math.PI * Math.sqrt( Math.PI * area ) );
		const n = resistance * resistance + reactance * reactance;
		const loadR = resistance * reactance * reactance / n, loadI = resistance * resistance * reactance / n;
		dr += K[ 4 ] * loadR - K[ 5 ] * loadI;
		di += K[ 4 ] * loadI + K[ 5 ] * loadR;

	}

	const dn = dr * dr + di * di;
	out[ 0 ] = dr / dn;
	out[ 1 ] = - di / dn;
	return out;

}

let grid = null;
let decibels = null;
const H = new Float64Array( 2 );

/**
 * The first `count` formants of the tube: out.frequencies and out.bandwidths (Hz), NaN where the
 * band (TUBE_FORMANT_BAND_HZ) holds fewer peaks; peaks found on a TUBE_GRID_STEP_HZ grid and each
 * refined by a parabola through its three dB values; the bandwidth is the peak's width 3 dB down.
 */
export function tubeFormants( lengths, areas, { count = FORMANT_COUNT, lossy = true } = {}, out = { frequencies: new Float64Array( count ), bandwidths: new Float64Array( count ) } ) {

	const step = TUBE_GRID_STEP_HZ;
	if ( grid === null ) {

		const [ low, high ] = TUBE_FORMANT_BAND_HZ;
		const n = Math.floor( ( high - low ) / step + 0.5 ) + 1;
		grid = new Float64Array( n );
		decibels = new Float64Array( n );
		for ( let i = 0; i < n; i ++ ) grid[ i ] = low + i * step;

	}

	for ( let i = 0; i < grid.length; i ++ ) {

		tubeTransfer( lengths, areas, grid[ i ], lossy, H );
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
