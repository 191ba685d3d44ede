// Vite configuration for the browser app. `vite build web` writes web/dist, which the API server
// serves at `/`. In development (`vite web`), API and asset requests go to a local server.

import { fileURLToPath } from 'node:url';
import { defineConfig } from 'vite';

const apiTarget = process.env.GLASSHEAD_API_URL ?? 'http://127.0.0.1:8000';

export default defineConfig( {
	root: fileURLToPath( new URL( '.', import.meta.url ) ),
	base: '/',
	build: {
		outDir: 'dist',
		emptyOutDir: true,
		target: 'es2022',
		// three.js alone is about 700 kB minified; it is one cacheable chunk, loaded with the head view.
		chunkSizeWarningLimit: 900,
	},
	server: {
		proxy: {
			'/api': apiTarget,
			'/assets': apiTarget,
		},
	},
} );
