// Median of the most recent frame times: a ring buffer and a scratch array, both allocated once.

export class FrameTimer {

	constructor( capacity = 60 ) {

		if ( ! Number.isInteger( capacity ) || capacity < 1 ) throw new RangeError( `capacity must be a positive integer, got ${ capacity }` );
		this.samples = new Float64Array( capacity );
		this.scratch = new Float64Array( capacity );
		this.count = 0;
		this.next = 0;

	}

	/** Record one frame time in milliseconds (ignored unless finite and non-negative). */
	add( ms ) {

		if ( ! ( ms >= 0 ) || ms === Infinity ) return;
		this.samples[ this.next ] = ms;
		this.next = ( this.next + 1 ) % this.samples.length;
		this.count = Math.min( this.count + 1, this.samples.length );

	}

	/** Median of the recorded times in milliseconds, or null when none are recorded. */
	median() {

		const n = this.count;
		if ( n === 0 ) return null;
		const sorted = this.scratch.subarray( 0, n );
		sorted.set( this.samples.subarray( 0, n ) );
		sorted.sort();
		return n % 2 ? sorted[ ( n - 1 ) / 2 ] : ( sorted[ n / 2 - 1 ] + sorted[ n / 2 ] ) / 2;

	}

}
