// Serves the app (API, assets and web bundle) at http://$HOST:$PORT (default 127.0.0.1:8000).
import { join } from 'node:path';
import { REPO, run } from './lib.mjs';

const host = process.env.HOST ?? '127.0.0.1';
const port = process.env.PORT ?? '8000';
console.log( `Glasshead at http://${host}:${port}/  (API docs at /api/v1/docs; Ctrl-C stops it)` );
run( join( REPO, '.venv', 'bin', 'glasshead' ), [ 'serve' ] );
