// The complex roots of a real polynomial by the Aberth-Ehrlich iteration (Aberth 1973, "Iteration
// methods for finding all zeros of a polynomial simultaneously", Math. Comp. 27, 339-344; Bini
// 1996, "Numerical computation of polynomial zeros by means of Aberth's method", Numer. Algorithms
// 13, 179-200): all roots are refined together, each Newton step corrected by the pull of the
// others, w_k = N_k / ( 1 - N_k sum_{j != k} 1 / (z_k - z_j) ), N_k = p(z_k) / p'(z_k). It
// converges cubically to simple roots from starting points spread on a circle, with no deflation
// (so no error carried from one root to the next), which suits the LPC polynomials of formant
// analysis: degree 10 or so, roots inside the unit circle, some close together.

/** Iterations allowed; order-10 LPC polynomials take 6 to 12. */
const MAX_ITERATIONS = 80;
/** A root has converged when its last correction is below this, relative to max(1, |z|). */
const TOLERANCE = 1e-13;

/**
 * Roots of c[0] z^n + c[1] z^(n-1) + ... + c[n] (c[0] != 0), into re[0..n), im[0..n). Allocates
 * nothing. Returns the iterations taken (MAX_ITERATIONS when it stopped short of the tolerance,
 * with the roots as good as they got).
 * @param {Float64Array} c n + 1 coefficients, highest power first
 * @param {number} n degree
 * @param {Float64Array} re receives the real parts
 * @param {Float64Array} im receives the imaginary parts
 * @param {Uint8Array} done scratch of n flags
 * @returns {number}
 */
export function polynomialRoots( c, n, re, im, done ) {

	if ( n < 1 ) return 0;
	const lead = c[ 0 ];
	if ( lead === 0 ) throw new RangeError( 'polynomialRoots: the leading coefficient is 0' );
	// Start on a circle of the roots' geometric mean radius |c[n] / c[0]|^(1/n), at angles offset
	// from the real axis so that no start is its own conjugate's (which would keep pairs real).
	let radius = Math.pow( Math.abs( c[ n ] / lead ), 1 / n );
	if ( ! ( radius > 1e-3 ) || ! Number.isFinite( radius ) ) radius = 0.5;
	for ( let k = 0; k < n; k ++ ) {

		const angle = 2 * Math.PI * k / n + 0.4;
		re[ k ] = radius * Math.cos( angle );
		im[ k ] = radius * Math.sin( angle );
		done[ k ] = 0;

	}

	let iteration = 0;
	for ( ; iteration < MAX_ITERATIONS; iteration ++ ) {

		let active = 0;
		for ( let k = 0; k < n; k ++ ) {

			if ( done[ k ] ) continue;
			active ++;
			const zr = re[ k ], zi = im[ k ];
			// Horner for p(z) and p'(z) at once.
			let pr = lead, pi = 0, dr = 0, di = 0;
			for ( let i = 1; i <= n; i ++ ) {

				const ndr = dr * zr - di * zi + pr, ndi = dr * zi + di * zr + pi;
				dr = ndr; di = ndi;
				const npr = pr * zr - pi * zi + c[ i ], npi = pr * zi + pi * zr;
				pr = npr; pi = npi;

			}

			if ( pr === 0 && pi === 0 ) {

				done[ k ] = 1;
				continue;

			}

			// N = p / p'.
			const dd = dr * dr + di * di;
			if ( dd === 0 ) {

				// A critical point: nudge off it.
				re[ k ] += 1e-3 * ( 1 + Math.abs( zr ) );
				im[ k ] += 1e-3 * ( 1 + Math.abs( zi ) );
				continue;

			}

			const nr = ( pr * dr + pi * di ) / dd, ni = ( pi * dr - pr * di ) / dd;
			// S = sum over the other roots of 1 / (z - z_j).
			let sr = 0, si = 0;
			for ( let j = 0; j < n; j ++ ) {

				if ( j === k ) continue;
				const ur = zr - re[ j ], ui = zi - im[ j ];
				const uu = ur * ur + ui * ui;
				if ( uu === 0 ) continue;
				sr += ur / uu;
				si -= ui / uu;

			}

			// w = N / (1 - N S).
			const qr = 1 - ( nr * sr - ni * si ), qi = - ( nr * si + ni * sr );
			const qq = qr * qr + qi * qi;
			const wr = qq === 0 ? nr : ( nr * qr + ni * qi ) / qq;
			const wi = qq === 0 ? ni : ( ni * qr - nr * qi ) / qq;
			re[ k ] = zr - wr;
			im[ k ] = zi - wi;
			// Squared sizes: Math.hypot would box its arguments on every call.
			if ( wr * wr + wi * wi <= TOLERANCE * TOLERANCE * Math.max( 1, zr * zr + zi * zi ) ) done[ k ] = 1;

		}

		if ( active === 0 ) break;

	}

	return iteration;

}

/**
 * Reflect roots outside the unit circle to 1 / conj(z), inside it (as Praat's
 * Roots_fixIntoUnitCircle): the same frequencies, and a stable filter. In place.
 */
export function fixIntoUnitCircle( re, im, n ) {

	for ( let k = 0; k < n; k ++ ) {

		const rr = re[ k ] * re[ k ] + im[ k ] * im[ k ];
		if ( rr > 1 ) {

			re[ k ] /= rr;
			im[ k ] /= rr;

		}

	}

}
