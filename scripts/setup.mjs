// Brings a checkout up to date for `npm start` and `npm test`: installs what is missing and
// rebuilds what is stale. Every step keeps a stamp (a hash of its inputs), so a second run with
// nothing changed takes seconds.
//
//   node scripts/setup.mjs [start|test]
import { existsSync, mkdirSync, readFileSync, writeFileSync } from 'node:fs';
import { join } from 'node:path';
import { hashInputs, REPO, run, step } from './lib.mjs';

const mode = process.argv[ 2 ] ?? 'start';
const STAMPS = join( REPO, '.setup-stamps' );
mkdirSync( STAMPS, { recursive: true } );

function stale( name, digest ) {
	const file = join( STAMPS, name );
	return ! existsSync( file ) || readFileSync( file, 'utf8' ) !== digest;
}

function stamp( name, digest ) {
	writeFileSync( join( STAMPS, name ), digest );
}

function ensurePython() {
	const venvPython = join( REPO, '.venv', 'bin', 'python' );
	const digest = hashInputs( [ 'pyproject.toml' ] );
	if ( existsSync( venvPython ) && ! stale( 'venv', digest ) ) return;
	step( 'Python environment (.venv)', () => {
		if ( ! existsSync( venvPython ) ) {
			const python = process.env.PYTHON ?? 'python3';
			run( python, [ '-c', 'import sys; sys.exit(sys.version_info < (3, 11))' ], {
				hint: `${python} 3.11 or newer is required (set PYTHON to another interpreter)`,
			} );
			run( python, [ '-m', 'venv', '.venv' ] );
			run( venvPython, [ '-m', 'pip', 'install', '--quiet', '--upgrade', 'pip' ] );
		}
		installProject( venvPython );
	} );
	stamp( 'venv', digest );
}

/**
 * The project and its dev extras into the environment, with uv (from PyPI, into the environment
 * itself) when it installs: it fetches and unpacks in parallel, 7 s where pip takes 28 s on a
 * 2-core machine, and resolves the same versions. pip does it when uv cannot be had.
 */
function installProject( venvPython ) {
	const uv = join( REPO, '.venv', 'bin', 'uv' );
	const gotUv = existsSync( uv ) || succeeds( venvPython, [ '-m', 'pip', 'install', '--quiet', 'uv' ] );
	if ( gotUv && succeeds( uv, [ 'pip', 'install', '--quiet', '--python', venvPython, '-e', '.[dev]' ] ) ) return;
	if ( gotUv ) console.log( '    uv could not install the project; pip does' );
	run( venvPython, [ '-m', 'pip', 'install', '--quiet', '-e', '.[dev]' ] );
}

/** Run a command; true when it succeeded (its output is shown, a failure is not fatal). */
function succeeds( command, args ) {
	return run( command, args, { allowFailure: true } ) === 0;
}

function ensureNodeModules() {
	const digest = hashInputs( [ 'package.json', 'package-lock.json' ] );
	if ( existsSync( join( REPO, 'node_modules' ) ) && ! stale( 'node_modules', digest ) ) return;
	step( 'Node modules', () => run( 'npm', [ 'ci', '--no-audit', '--no-fund', '--loglevel=error' ] ) );
	stamp( 'node_modules', digest );
}

/**
 * Installs a Debian package with apt-get when its file is missing and we run as root; prints
 * the command to run and exits otherwise. apt-get update runs once a run.
 */
let aptUpdated = false;
function ensureDebianPackage( { file, pkg, why } ) {
	if ( existsSync( file ) ) return;
	const isRoot = process.getuid?.() === 0;
	if ( ! isRoot ) {
		console.error( `${why} needs Debian's ${pkg} (${file}).\n` +
			`Install it with:  sudo apt-get install ${pkg}` );
		process.exit( 1 );
	}
	step( `Debian ${pkg} (apt-get)`, () => {
		if ( ! aptUpdated ) run( 'apt-get', [ 'update', '-qq' ] );
		aptUpdated = true;
		run( 'apt-get', [ 'install', '-y', '-qq', pkg ], { env: { DEBIAN_FRONTEND: 'noninteractive' } } );
	} );
}

function ensureChromium() {
	ensureDebianPackage( { file: '/usr/bin/chromium', pkg: 'chromium',
		why: 'The end-to-end tests' } );
}

function ensureEspeak() {
	// The utterance route's phone timings and voice (docs/speech.md).
	ensureDebianPackage( { file: '/usr/bin/espeak-ng', pkg: 'espeak-ng', why: 'Speech (POST /utterances)' } );
}

function ensurePostgres() {
	// The tests that run the API as several workers against a real PostgreSQL server.
	ensureDebianPackage( { file: '/usr/lib/postgresql/15/bin/initdb', pkg: 'postgresql',
		why: 'The PostgreSQL tests (tests/postgres_support.py)' } );
}

function buildAssets() {
	// `glasshead build` hashes its own inputs and returns at once when nothing changed.
	run( join( REPO, '.venv', 'bin', 'glasshead' ), [ 'build' ] );
}

function buildWeb() {
	const digest = hashInputs( [ 'web', 'package-lock.json' ], { exclude: [ 'web/dist' ] } );
	if ( existsSync( join( REPO, 'web', 'dist', 'index.html' ) ) && ! stale( 'web', digest ) ) return;
	step( 'Web bundle (vite build)', () =>
		run( join( REPO, 'node_modules', '.bin', 'vite' ), [ 'build', 'web', '--logLevel', 'warn' ] ) );
	stamp( 'web', digest );
}

ensurePython();
ensureNodeModules();
ensureEspeak();
if ( mode === 'test' ) ensureChromium();
if ( mode === 'test' ) ensurePostgres();
buildAssets();
buildWeb();
