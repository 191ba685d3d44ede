// Counting garbage collections during a loop, to show that a per-frame kernel allocates nothing.
//
// A collection can also be started by work that is not the loop's (the JIT finishing a
// compilation in the background, the test runner itself), so the count that matters is the
// fewest over a few runs: a kernel that allocates on every call collects in every run. V8's GC
// profiler records each collection between start() and stop() as it happens: nothing waits for
// the collections to be reported, however busy the machine.
import { GCProfiler } from 'node:v8';

/** Garbage collections that started while ``run()`` ran. */
export async function garbageCollections( run ) {

	const profiler = new GCProfiler();
	profiler.start();
	run();
	return profiler.stop().statistics.length;

}

/** The fewest garbage collections over ``attempts`` runs of ``run()``. */
export async function fewestGarbageCollections( run, attempts = 3 ) {

	let fewest = Infinity;
	for ( let k = 0; k < attempts && fewest > 0; k ++ ) fewest = Math.min( fewest, await garbageCollections( run ) );
	return fewest;

}
