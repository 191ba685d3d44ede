// Runs every benchmark: the JavaScript ones in Node (*.bench.mjs) and the Python ones (*.py).
// Each prints its own medians and its ratio against a baseline measured in the same run.
import { spawnSync } from 'node:child_process';
import { readdirSync } from 'node:fs';
import { dirname, join } from 'node:path';
import { fileURLToPath } from 'node:url';

const here = dirname( fileURLToPath( import.meta.url ) );
const python = join( here, '..', '.venv', 'bin', 'python' );
const only = process.argv.slice( 2 );
let failures = 0;
for ( const name of readdirSync( here ).sort() ) {
	if ( only.length && ! only.some( ( word ) => name.includes( word ) ) ) continue;
	const command = name.endsWith( '.bench.mjs' ) ? process.execPath : name.endsWith( '.py' ) ? python : null;
	if ( ! command ) continue;
	console.log( `\n==> ${name}` );
	const result = spawnSync( command, [ join( here, name ) ], { stdio: 'inherit', cwd: join( here, '..' ) } );
	if ( result.status !== 0 ) failures ++;
}
process.exit( failures ? 1 : 0 );
