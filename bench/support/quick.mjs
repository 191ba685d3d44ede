// Shared by the benchmarks: the quick pass and the correctness checks.
//
// GLASSHEAD_BENCH_QUICK=1 (set by `node bench/run.mjs --quick`, which `npm test` runs) cuts every
// benchmark to a few iterations: its timings then mean little, but it still loads what the app
// loads, runs every method and makes every check, so that a benchmark that breaks or stops
// checking fails the suite. Timing goals are reported, never enforced; a failed check makes the
// process exit non-zero.

/** Whether this is the quick pass. */
export const QUICK = process.env.GLASSHEAD_BENCH_QUICK === '1';

/** `full` in a full run, `quick` in the quick pass. */
export const count = ( full, quick ) => ( QUICK ? quick : full );

const failures = [];

/**
 * Record a correctness check: prints `check: <what>: ok` or `check: <what>: FAILED (<detail>)`
 * and, when it failed, sets the exit code to 1. Returns ok.
 */
export function check( what, ok, detail = '' ) {

	console.log( `check: ${ what }: ${ ok ? 'ok' : `FAILED${ detail ? ` (${ detail })` : '' }` }` );
	if ( ! ok ) {

		failures.push( what );
		process.exitCode = 1;

	}

	return ok;

}

/** The checks that failed so far. */
export const failedChecks = () => failures.slice();
