// Shared by the benchmarks: a seeded generator, so every run draws the same poses, and medians.

/** mulberry32: a small seeded generator of uniform numbers in [0, 1). */
export function random( seed ) {

	let a = seed >>> 0;
	return () => {

		a = ( a + 0x6D2B79F5 ) >>> 0;
		let t = a;
		t = Math.imul( t ^ ( t >>> 15 ), t | 1 );
		t ^= t + Math.imul( t ^ ( t >>> 7 ), t | 61 );
		return ( ( t ^ ( t >>> 14 ) ) >>> 0 ) / 4294967296;

	};

}

/** The median of an array of numbers. */
export function median( values ) {

	const sorted = Float64Array.from( values ).sort();
	const mid = sorted.length >> 1;
	return sorted.length % 2 ? sorted[ mid ] : 0.5 * ( sorted[ mid - 1 ] + sorted[ mid ] );

}
