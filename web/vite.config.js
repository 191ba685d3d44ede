// Vite configuration for the browser app. `vite build web` writes web/dist, which the API server
// serves at `/`. In development (`vite web`), API and asset requests go to a local server.

import { readdirSync, readFileSync, statSync, writeFileSync } from 'node:fs';
import { join } from 'node:path';
import { fileURLToPath } from 'node:url';
import { gzipSync } from 'node:zlib';
import { defineConfig } from 'vite';

const outDir = fileURLToPath( new URL( 'dist', import.meta.url ) );

/**
 * Write a gzip sibling (`name.gz`) of every text file of the bundle over 1 KiB that gzip shrinks
 * by 5 % or more; the server sends it to browsers that accept gzip (server/glasshead/pipeline/
 * precompress.py does the same for the built assets, with the same rules).
 */
function precompress() {

	return {
		name: 'glasshead-precompress',
		apply: 'build',
		closeBundle() {

			const walk = ( dir ) => readdirSync( dir, { withFileTypes: true } ).flatMap( ( entry ) => ( entry.isDirectory() ? walk( join( dir, entry.name ) ) : [ join( dir, entry.name ) ] ) );
			for ( const file of walk( outDir ) ) {

				if ( ! /\.(js|css|html|svg|json|txt)$/.test( file ) || statSync( file ).size < 1024 ) continue;
				const data = readFileSync( file );
				const packed = gzipSync( data, { level: 9 } );
				if ( packed.length <= 0.95 * data.length ) writeFileSync( `${ file }.gz`, packed );

			}

		},
	};

}

const apiTarget = process.env.GLASSHEAD_API_URL ?? 'http://127.0.0.1:8000';

export default defineConfig( {
	root: fileURLToPath( new URL( '.', import.meta.url ) ),
	base: '/',
	plugins: [ precompress() ],
	build: {
		outDir: 'dist',
		emptyOutDir: true,
		target: 'es2022',
		// three.js alone is about 700 kB minified; it is one cacheable chunk, loaded with the head view.
		chunkSizeWarningLimit: 900,
		// Scripts referenced by URL (the microphone's AudioWorklet) stay files: the page's CSP
		// runs scripts from this origin only, never from a data: URL.
		assetsInlineLimit: ( file ) => ( /\.js$/.test( file ) ? false : undefined ),
	},
	server: {
		proxy: {
			'/api': apiTarget,
			'/assets': apiTarget,
		},
	},
} );
