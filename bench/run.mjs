// Runs every benchmark: the JavaScript ones in Node (*.bench.mjs) and the Python ones (*.py).
// Each prints its own medians and its ratio against a baseline measured in the same run, and
// exits non-zero when one of its correctness checks fails (or it breaks). The last lines name
// the benchmarks that failed and count them: `bench: N passed, M failed`.
//
//   node bench/run.mjs [--quick] [word ...]
//
// Words pick the benchmarks whose file name contains one of them. --quick runs each with
// GLASSHEAD_BENCH_QUICK=1: a few iterations, every check still made (`npm test` runs this).
import { spawnSync } from 'node:child_process';
import { readdirSync } from 'node:fs';
import { dirname, join } from 'node:path';
import { fileURLToPath } from 'node:url';

const here = dirname( fileURLToPath( import.meta.url ) );
const python = join( here, '..', '.venv', 'bin', 'python' );
const args = process.argv.slice( 2 );
const quick = args.includes( '--quick' );
const only = args.filter( ( word ) => word !== '--quick' );
const env = { ...process.env, ...( quick ? { GLASSHEAD_BENCH_QUICK: '1' } : {} ) };
const started = Date.now();
const passed = [];
const failed = [];
for ( const name of readdirSync( here ).sort() ) {

	if ( only.length && ! only.some( ( word ) => name.includes( word ) ) ) continue;
	const command = name.endsWith( '.bench.mjs' ) ? process.execPath : name.endsWith( '.py' ) ? python : null;
	if ( ! command ) continue;
	console.log( `\n==> ${ name }` );
	const begun = Date.now();
	const result = spawnSync( command, [ join( here, name ) ], { stdio: 'inherit', cwd: join( here, '..' ), env } );
	const seconds = ( ( Date.now() - begun ) / 1000 ).toFixed( 1 );
	if ( result.status === 0 ) {

		passed.push( name );
		console.log( `<== ${ name }: passed (${ seconds } s)` );

	} else {

		const why = result.error ? result.error.message : result.signal ? `killed by ${ result.signal }` : `exit ${ result.status }`;
		failed.push( `${ name } (${ why })` );
		console.log( `<== ${ name }: FAILED, ${ why } (${ seconds } s)` );

	}

}

console.log( `\n${ quick ? 'Quick pass' : 'Benchmarks' } took ${ ( ( Date.now() - started ) / 1000 ).toFixed( 0 ) } s.` );
if ( failed.length ) console.log( `Failed benchmarks: ${ failed.join( ', ' ) }` );
console.log( `bench: ${ passed.length } passed, ${ failed.length } failed` );
process.exit( failed.length || passed.length === 0 ? 1 : 0 );
