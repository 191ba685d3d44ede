// What the views load through the HTTP client (web/src/ui/shared/loaders.js), on a client whose fetch is a
// stand-in: the requests made, and what a missing asset leaves behind.
import { test } from 'node:test';
import assert from 'node:assert/strict';

import { ApiError, createApi } from '../../web/src/api.js';
import { loadArticulationData, loadEpgLayout, loadTablesWhenMoved } from '../../web/src/ui/shared/loaders.js';

/** A client answering `routes` (path under /api/v1 -> [status, body]) and recording the paths asked. */
function fakeApi( routes ) {

	const asked = [];
	const api = createApi( { fetchImpl: async ( url ) => {

		const path = url.replace( '/api/v1/', '' );
		asked.push( path );
		const [ status, body ] = routes[ path ] ?? [ 404, { detail: `no route ${ path }` } ];
		return { ok: status < 300, status, statusText: '', json: async () => body };

	} } );
	return { api, asked };

}

test( 'the electrode layout is loaded for every grid, the contact settings from the first', async () => {

	const { api, asked } = fakeApi( {
		'epg/layout?grid=reading62': [ 200, { grid: 'reading62', contact: { tolerance_mm: 1 }, midline: [ 1 ] } ],
		'epg/layout?grid=dense96': [ 200, { grid: 'dense96', contact: { tolerance_mm: 2 }, midline: [ 2 ] } ],
	} );
	const layout = await loadEpgLayout( { api } );
	assert.deepEqual( asked.sort(), [ 'epg/layout?grid=dense96', 'epg/layout?grid=reading62' ] );
	assert.equal( layout.grids.reading62.grid, 'reading62' );
	assert.equal( layout.grids.dense96.grid, 'dense96' );
	assert.deepEqual( layout.contact, { tolerance_mm: 1 } );
	assert.deepEqual( layout.midline, [ 1 ] );
	const reading = await loadEpgLayout( { api, grids: [ 'reading62' ] } );
	assert.deepEqual( Object.keys( reading.grids ), [ 'reading62' ] );

} );

test( 'the articulation\'s data: tables, face rig and velum rig that cannot be had are null with the reason; no tongue rig rejects', async () => {

	const rig = { format_version: 1, parameters: [] };
	const { api, asked } = fakeApi( {
		'tongue/rig': [ 200, rig ],
		'collision/tables': [ 503, { detail: 'collision tables not built: run `glasshead build`' } ],
		'face/rig': [ 200, { format_version: 1 } ],
	} );
	const data = await loadArticulationData( { api } );
	assert.deepEqual( asked.sort(), [ 'collision/tables', 'face/rig', 'tongue/rig', 'velum/rig' ] );
	assert.deepEqual( data.definition, rig );
	assert.equal( data.velum, null );
	assert.equal( data.velumError, 'GET /api/v1/velum/rig failed with HTTP 404: no route velum/rig' );
	assert.equal( data.tables, null );
	assert.equal( data.tablesError, 'GET /api/v1/collision/tables failed with HTTP 503: collision tables not built: run `glasshead build`' );
	assert.deepEqual( data.face, { format_version: 1 } );
	assert.equal( data.faceRigError, null );

	const { api: bare } = fakeApi( {} );
	await assert.rejects( loadArticulationData( { api: bare } ), ( error ) => error instanceof ApiError && error.status === 404 && /tongue\/rig/.test( error.message ) );

} );

test( 'collision tables of another format version are refused before their binary is asked for', async () => {

	const { api, asked } = fakeApi( {
		'tongue/rig': [ 200, {} ],
		'collision/tables': [ 200, { format_version: 99, url: '/assets/build/collision-tables.bin' } ],
		'face/rig': [ 503, { detail: 'face rig not built' } ],
		'velum/rig': [ 200, { format_version: 1 } ],
	} );
	const data = await loadArticulationData( { api } );
	assert.deepEqual( data.velum, { format_version: 1 } );
	assert.equal( data.velumError, null );
	assert.match( data.tablesError, /format version 99/ );
	assert.match( data.faceRigError, /HTTP 503: face rig not built/ );
	assert.ok( ! asked.some( ( path ) => path.includes( '.bin' ) ) );

} );

test( 'the head view\'s collision tables are asked for only once the tongue leaves its rest pose, and once', async () => {

	const { api, asked } = fakeApi( {
		'tongue/rig': [ 200, {} ],
		'collision/tables': [ 200, { format_version: 99, url: '/assets/build/collision-tables.bin' } ],
	} );
	const data = await loadArticulationData( { api, tables: false } );
	assert.equal( data.tables, null );
	assert.equal( data.tablesError, null );
	assert.ok( ! asked.includes( 'collision/tables' ), asked.join( ', ' ) );

	const hooks = new Set();
	const viewer = { onFrame: ( fn ) => ( hooks.add( fn ), () => hooks.delete( fn ) ), requestRender() {} };
	const frame = () => [ ...hooks ].forEach( ( fn ) => fn() );
	const articulation = { state: { version: 4 }, tables: null, tablesError: null, unregister: [], update() {} };
	const warn = console.warn;
	const warned = [];
	console.warn = ( message ) => warned.push( message );
	try {

		loadTablesWhenMoved( articulation, viewer, { api } );
		frame();
		frame();
		assert.equal( asked.filter( ( path ) => path === 'collision/tables' ).length, 0, 'at rest' );
		// The watcher reports no change, or a still head would be drawn every frame.
		assert.deepEqual( [ ...hooks ].map( ( fn ) => fn() ), [ false ] );
		articulation.state.version = 5;
		frame();
		frame();
		await new Promise( ( resolve ) => setTimeout( resolve, 10 ) );
		assert.equal( asked.filter( ( path ) => path === 'collision/tables' ).length, 1, 'once moved' );
		assert.equal( hooks.size, 0 );
		assert.match( articulation.tablesError, /format version 99/ );
		assert.equal( articulation.tables, null );
		assert.equal( warned.length, 1 );

	} finally {

		console.warn = warn;

	}

	const disposed = { state: { version: 1 }, tables: null, unregister: [] };
	loadTablesWhenMoved( disposed, viewer, { api } );
	disposed.unregister.forEach( ( stop ) => stop() );
	assert.equal( hooks.size, 0, 'dispose() stops watching' );

} );
