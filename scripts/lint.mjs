// Static checks: ruff (Python style and bugs), import-linter (the Python packages' layers and
// forbidden imports, [tool.importlinter] in pyproject.toml), mypy (types of every Python package,
// [tool.mypy]) and eslint (JavaScript). Prints one line per check and exits non-zero when any
// fails.
//
//   node scripts/lint.mjs
import { spawnSync } from 'node:child_process';
import { join } from 'node:path';
import { REPO } from './lib.mjs';

const venv = ( name ) => join( REPO, '.venv', 'bin', name );
const CHECKS = [
	{ name: 'ruff', command: venv( 'ruff' ), args: [ 'check', 'server', 'tests', 'bench' ] },
	{ name: 'imports', command: venv( 'lint-imports' ), args: [] },
	{ name: 'mypy', command: venv( 'mypy' ), args: [] },
	{ name: 'eslint', command: join( REPO, 'node_modules', '.bin', 'eslint' ), args: [ 'web/src', 'e2e', 'bench', 'scripts', 'tests/js' ] },
];

const failed = [];
for ( const check of CHECKS ) {
	const started = Date.now();
	const result = spawnSync( check.command, check.args, { cwd: REPO, encoding: 'utf8' } );
	const seconds = ( ( Date.now() - started ) / 1000 ).toFixed( 1 );
	if ( result.error || result.status !== 0 ) {
		failed.push( check.name );
		process.stdout.write( result.stdout ?? '' );
		process.stderr.write( result.stderr ?? '' );
		console.log( `✖ ${ check.name } failed (${ result.error?.message ?? `exit ${ result.status }` }, ${ seconds } s)` );
	} else {
		console.log( `✔ ${ check.name } (${ seconds } s)` );
	}
}
console.log( `lint: ${ CHECKS.length - failed.length } passed, ${ failed.length } failed` );
process.exit( failed.length ? 1 : 0 );
