// Counting garbage collections during a loop, to show that a per-frame kernel allocates nothing.
//
// A collection can also be started by work that is not the loop's (the JIT finishing a
// compilation in the background, the test runner itself), so the count that matters is the
// fewest over a few runs: a kernel that allocates on every call collects in every run.
import { PerformanceObserver, performance } from 'node:perf_hooks';

/** Garbage collections that started while ``run()`` ran. */
export async function garbageCollections( run ) {

	let count = 0;
	let start = 0;
	let end = Infinity;
	const observer = new PerformanceObserver( ( list ) => {

		for ( const entry of list.getEntries() ) if ( entry.startTime >= start && entry.startTime <= end ) count ++;

	} );
	observer.observe( { entryTypes: [ 'gc' ] } );
	start = performance.now();
	run();
	end = performance.now();
	await new Promise( ( resolve ) => setTimeout( resolve, 100 ) );
	observer.disconnect();
	return count;

}

/** The fewest garbage collections over ``attempts`` runs of ``run()``. */
export async function fewestGarbageCollections( run, attempts = 3 ) {

	let fewest = Infinity;
	for ( let k = 0; k < attempts && fewest > 0; k ++ ) fewest = Math.min( fewest, await garbageCollections( run ) );
	return fewest;

}
