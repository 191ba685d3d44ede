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
// another. `node scripts/test.mjs end-to-end python` runs the named suites alone, in that order.
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
	{ name: 'end-to-end', command: process.execPath, args: [ '--test', '--test-concurrency=1', '--test-reporter=spec', ...testFiles( 'e2e' ) ], around: withSharedServer },
	{ name: 'bench', command: process.execPath, args: [ join( REPO, 'bench', 'run.mjs' ), '--quick' ] },
];

const tally = { passed: 0, failed: 0, skipped: 0, todo: 0 };
const failedSuites = [];
const started = Date.now();

/**
 * The end-to-end files' one server: started here with a user of every role, its address, database
 * and users passed to each file (e2e/harness.js, e2e/accounts.js), so that each file does not
 * start its own server and make its own users (about 5 s of CPU a file). Files that start a
 * server of their own still do. GLASSHEAD_E2E_SERVER_PER_FILE=1 leaves each file its own.
 */
async function withSharedServer( run ) {
	if ( process.env.GLASSHEAD_E2E_SERVER_PER_FILE === '1' || process.env.GLASSHEAD_E2E_BASE_URL ) return run( {} );
	const { startServer } = await import( '../e2e/harness.js' );
	const { ROLES, createAccounts } = await import( '../e2e/accounts.js' );
	let server;
	try {
		server = await startServer();
		const users = await createAccounts( server, ROLES );
		return await run( {
			GLASSHEAD_E2E_BASE_URL: server.baseUrl,
			GLASSHEAD_E2E_DATABASE_URL: server.databaseUrl,
			GLASSHEAD_E2E_ACCOUNTS: JSON.stringify( { databaseUrl: server.databaseUrl, users } ),
		} );
	} catch ( error ) {
		return { status: 1, stdout: '', stderr: `could not start the end-to-end tests' server: ${ error.message }\n` };
	} finally {
		await server?.stop();
	}
}

/** Run one suite with its output held back, then print it under its heading and count it. */
async function runSuite( suite ) {
	const begun = Date.now();
	const around = suite.around ?? ( ( run ) => run( {} ) );
	const { status, stdout, stderr } = await around( ( env ) => spawnSuite( suite, env ) );
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
}

/** Run a suite's command with `env` added; resolves { status, stdout, stderr }. */
function spawnSuite( suite, env ) {
	return new Promise( ( resolve ) => {
		const child = spawn( suite.command, suite.args, { cwd: REPO, stdio: [ 'ignore', 'pipe', 'pipe' ], env: { ...process.env, ...env } } );
		let stdout = '';
		let stderr = '';
		child.stdout.setEncoding( 'utf8' ).on( 'data', ( chunk ) => ( stdout += chunk ) );
		child.stderr.setEncoding( 'utf8' ).on( 'data', ( chunk ) => ( stderr += chunk ) );
		child.on( 'error', ( error ) => ( stderr += `could not start ${suite.command}: ${error.message}\n` ) );
		child.on( 'close', ( status ) => resolve( { status, stdout, stderr } ) );
	} );
}

async function runLane( lane ) {
	for ( const suite of lane ) await runSuite( suite );
}

const byName = Object.fromEntries( suites.map( ( suite ) => [ suite.name, suite ] ) );
const named = process.argv.slice( 2 );
const unknown = named.filter( ( name ) => ! byName[ name ] );
if ( unknown.length ) {
	console.error( `no suite named ${ unknown.join( ', ' ) }: the suites are ${ Object.keys( byName ).join( ', ' ) }` );
	process.exit( 2 );
}
if ( named.length ) {
	await runLane( named.map( ( name ) => byName[ name ] ) );
} else if ( process.env.GLASSHEAD_TEST_LANES === '1' ) {
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
