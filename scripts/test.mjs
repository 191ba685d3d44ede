// Every test: static checks (ruff, mypy, eslint), Python (pytest, including the shared vectors),
// JavaScript unit tests (including the shared vectors), end-to-end tests in Debian's Chromium, and
// a quick pass of every benchmark (bench/run.mjs --quick: a few iterations each, every
// correctness check made, so that a benchmark that breaks or stops checking fails here; the full
// runs are `npm run bench`). Prints one closing tally.
//
// The suites run in two lanes side by side, lint then Python in one, JavaScript then the browser
// in the other: pytest keeps about one core busy and Chromium the other, so the whole run takes
// about as long as its longer lane instead of the sum. The benchmarks' quick pass (40 to 50 s of CPU)
// follows whichever lane ends first, in the time the other lane still takes. Each suite's output
// is printed whole when it ends, never interleaved. GLASSHEAD_TEST_LANES=1 runs them one after
// another.
import { spawn } from 'node:child_process';
import { existsSync, readdirSync } from 'node:fs';
import { join } from 'node:path';
import { REPO } from './lib.mjs';

function testFiles( dir ) {
	const full = join( REPO, dir );
	if ( ! existsSync( full ) ) return [];
	return readdirSync( full ).filter( ( name ) => name.endsWith( '.test.js' ) ).sort().map( ( name ) => join( dir, name ) );
}

const suites = [
	{ name: 'lint', command: process.execPath, args: [ join( REPO, 'scripts', 'lint.mjs' ) ] },
	{ name: 'python', command: join( REPO, '.venv', 'bin', 'pytest' ), args: [ '-p', 'no:cacheprovider', '--durations=30' ] },
	{ name: 'javascript', command: process.execPath, args: [ '--test', '--test-reporter=spec', ...testFiles( 'tests/js' ) ] },
	{ name: 'end-to-end', command: process.execPath, args: [ '--test', '--test-concurrency=1', '--test-reporter=spec', ...testFiles( 'e2e' ) ] },
	{ name: 'bench', command: process.execPath, args: [ join( REPO, 'bench', 'run.mjs' ), '--quick' ] },
];

const tally = { passed: 0, failed: 0, skipped: 0, todo: 0 };
const failedSuites = [];
const started = Date.now();

/** Run one suite with its output held back, then print it under its heading and count it. */
function runSuite( suite ) {
	return new Promise( ( resolve ) => {
		const begun = Date.now();
		const child = spawn( suite.command, suite.args, { cwd: REPO, stdio: [ 'ignore', 'pipe', 'pipe' ] } );
		let stdout = '';
		let stderr = '';
		child.stdout.setEncoding( 'utf8' ).on( 'data', ( chunk ) => ( stdout += chunk ) );
		child.stderr.setEncoding( 'utf8' ).on( 'data', ( chunk ) => ( stderr += chunk ) );
		child.on( 'error', ( error ) => ( stderr += `could not start ${suite.command}: ${error.message}\n` ) );
		child.on( 'close', ( status ) => {
			const seconds = ( ( Date.now() - begun ) / 1000 ).toFixed( 0 );
			console.log( `\n==> ${suite.name} tests (${seconds} s)` );
			process.stdout.write( stdout );
			process.stderr.write( stderr );
			const counts = countResults( suite.name, stdout );
			tally.passed += counts.passed;
			tally.failed += counts.failed;
			tally.skipped += counts.skipped;
			tally.todo += counts.todo ?? 0;
			if ( status !== 0 || counts.passed === 0 ) failedSuites.push( `${suite.name} (exit ${status}, ${counts.passed} passed)` );
			resolve();
		} );
	} );
}

async function runLane( lane ) {
	for ( const suite of lane ) await runSuite( suite );
}

const byName = Object.fromEntries( suites.map( ( suite ) => [ suite.name, suite ] ) );
if ( process.env.GLASSHEAD_TEST_LANES === '1' ) {
	await runLane( suites );
} else {
	const lanes = [ [ byName.lint, byName.python ], [ byName.javascript, byName[ 'end-to-end' ] ] ].map( runLane );
	await Promise.all( [ ...lanes, Promise.race( lanes ).then( () => runSuite( byName.bench ) ) ] );
}
console.log( `\nAll tests took ${( ( Date.now() - started ) / 1000 ).toFixed( 0 )} s.` );

console.log( failedSuites.length ? `\nFailed suites: ${failedSuites.join( ', ' )}` : '\nAll suites passed.' );
console.log( `${tally.passed} passed, ${tally.failed} failed, ${tally.skipped} skipped` + ( tally.todo ? `, ${tally.todo} todo (known shortfalls, named above)` : '' ) );
process.exit( failedSuites.length ? 1 : 0 );

function countResults( name, output ) {
	const number = ( pattern ) => Number( output.match( pattern )?.[ 1 ] ?? 0 );
	if ( name === 'lint' || name === 'bench' ) {
		// The runner's own closing line: the last `<name>: N passed, M failed`.
		const last = [ ...output.matchAll( new RegExp( `^${ name }: (\\d+) passed, (\\d+) failed$`, 'gm' ) ) ].pop();
		return { passed: Number( last?.[ 1 ] ?? 0 ), failed: Number( last?.[ 2 ] ?? 0 ), skipped: 0 };
	}
	if ( name === 'python' ) {
		const summary = output.trim().split( '\n' ).filter( ( line ) => / in [\d.]+s/.test( line ) ).pop() ?? '';
		return {
			passed: Number( summary.match( /(\d+) passed/ )?.[ 1 ] ?? 0 ),
			failed: Number( summary.match( /(\d+) failed/ )?.[ 1 ] ?? 0 ) + Number( summary.match( /(\d+) errors?/ )?.[ 1 ] ?? 0 ),
			skipped: Number( summary.match( /(\d+) skipped/ )?.[ 1 ] ?? 0 ),
		};
	}
	// A todo test is a known shortfall: it is counted and named in the tally, never hidden.
	return { passed: number( /ℹ pass (\d+)/ ), failed: number( /ℹ fail (\d+)/ ), skipped: number( /ℹ skipped (\d+)/ ), todo: number( /ℹ todo (\d+)/ ) };
}
