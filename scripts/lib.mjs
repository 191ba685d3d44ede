// Small helpers shared by the set-up, serve and test scripts.
import { spawnSync } from 'node:child_process';
import { createHash } from 'node:crypto';
import { readdirSync, readFileSync, statSync } from 'node:fs';
import { dirname, join, relative } from 'node:path';
import { fileURLToPath } from 'node:url';

export const REPO = join( dirname( fileURLToPath( import.meta.url ) ), '..' );

/** Runs a command in the repository; exits with its message and code when it fails. */
export function run( command, args, { hint, env, allowFailure = false } = {} ) {
	const result = spawnSync( command, args, {
		cwd: REPO, stdio: 'inherit', env: { ...process.env, ...env },
	} );
	if ( result.error ) {
		console.error( `Could not run ${command}: ${result.error.message}` + ( hint ? `\n${hint}` : '' ) );
		process.exit( 1 );
	}
	if ( result.status !== 0 && ! allowFailure ) {
		console.error( `${command} ${args.join( ' ' )} failed (exit ${result.status})` + ( hint ? `\n${hint}` : '' ) );
		process.exit( result.status ?? 1 );
	}
	return result.status;
}

/** Runs ``fn`` under a heading and prints how long it took. */
export function step( title, fn ) {
	const started = Date.now();
	console.log( `==> ${title}` );
	fn();
	console.log( `    done in ${( ( Date.now() - started ) / 1000 ).toFixed( 1 )} s` );
}

function listFiles( path, exclude, out ) {
	const rel = relative( REPO, path );
	if ( exclude.includes( rel ) || rel.split( '/' ).includes( 'node_modules' ) ) return out;
	const stats = statSync( path, { throwIfNoEntry: false } );
	if ( ! stats ) return out;
	if ( stats.isDirectory() ) {
		for ( const name of readdirSync( path ).sort() ) listFiles( join( path, name ), exclude, out );
	} else {
		out.push( path );
	}
	return out;
}

/** A SHA-256 over the names and contents of the given files and folders (relative to the repo). */
export function hashInputs( paths, { exclude = [] } = {} ) {
	const hash = createHash( 'sha256' );
	for ( const path of paths ) {
		for ( const file of listFiles( join( REPO, path ), exclude, [] ) ) {
			hash.update( relative( REPO, file ) ).update( '\0' ).update( readFileSync( file ) ).update( '\0' );
		}
	}
	return hash.digest( 'hex' );
}
