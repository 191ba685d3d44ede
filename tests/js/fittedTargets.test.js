// The fitted targets source (web/src/ui/shared/targets.js FittedTargets) on a fake HTTP client: the
// finished fits it lists, and a fit's frame from POST /epg/contacts with its params.
import { test } from 'node:test';
import assert from 'node:assert/strict';

import { createApi } from '../../web/src/api.js';
import { epgBasisText, FittedTargets, fitDescription, targetSources } from '../../web/src/ui/shared/targets.js';

const FRONT = [ '01111110', '11000011', '00000000', '00000000', '00000000', '00000000', '00000000', '00000000' ];
const PARAMS = { tip_height: 4.5, jaw_opening: 0, lip_opening: 1, velum_opening: 0.76 };

/** A fake client: answers by method and path, recording every request. */
function fakeApi( routes ) {

	const requests = [];
	const api = createApi( { fetchImpl: async ( url, init ) => {

		const key = `${ init.method } ${ url.replace( '/api/v1/', '' ) }`;
		requests.push( { key, body: init.body === undefined ? undefined : JSON.parse( init.body ) } );
		const route = routes[ key ];
		const [ status, body ] = route ? route( init ) : [ 404, { detail: `no route ${ key }` } ];
		return { ok: status < 300, status, statusText: '', json: async () => body };

	} } );
	return { api, requests };

}

const ROUTES = {
	'GET fits?state=done&limit=1000': () => [ 200, { total: 2, fits: [
		{ id: 12, name: 'my /t/', kind: 'epg', state: 'done', report: { rms_mm: 1.234, agreement: 0.871 } },
		{ id: 9, name: 'JD3 /a/', kind: 'contour', state: 'done', report: { rms_mm: 1.0 } },
	] } ],
	'GET fits/12': () => [ 200, { id: 12, name: 'my /t/', kind: 'epg', state: 'done', params: PARAMS } ],
	'GET fits/13': () => [ 200, { id: 13, name: 'busy', kind: 'contour', state: 'running', params: null } ],
	'POST epg/contacts': () => [ 200, { rows: FRONT } ],
};

test( 'the finished fits are listed by name with what they were fitted to and how closely', async () => {

	const { api, requests } = fakeApi( ROUTES );
	const list = await new FittedTargets( { api } ).list();
	assert.deepEqual( list, [
		{ id: '12', label: 'my /t/', description: 'epg fit, RMS 1.23 mm, EPG agreement 87 %' },
		{ id: '9', label: 'JD3 /a/', description: 'contour fit, RMS 1.00 mm' },
	] );
	assert.deepEqual( requests.map( ( r ) => r.key ), [ 'GET fits?state=done&limit=1000' ] );

} );

test( 'a fitted target is one frame: the synthetic EPG of its params, as a saved pose\'s', async () => {

	const { api, requests } = fakeApi( ROUTES );
	const target = await new FittedTargets( { api } ).frames( '12' );
	assert.deepEqual( target.rows, [ FRONT ] );
	assert.equal( target.t_s, null );
	assert.equal( target.label, 'my /t/' );
	assert.deepEqual( target.params, PARAMS );
	assert.deepEqual( target.reference, { label: 'my /t/', frames: [ FRONT ] } );
	assert.deepEqual( requests[ 1 ], { key: 'POST epg/contacts', body: { params: PARAMS } } );

} );

test( 'a fit that is not done has no target, and says why', async () => {

	const { api, requests } = fakeApi( ROUTES );
	await assert.rejects( new FittedTargets( { api } ).frames( '13' ), /fit 13 is running/ );
	assert.equal( requests.length, 1 );

} );

test( 'the fitted targets are the chooser\'s third source, named fit:<id>', () => {

	const sources = targetSources( { api: fakeApi( ROUTES ).api } );
	assert.deepEqual( sources.map( ( s ) => [ s.kind, s.title ] ), [ [ 'pose', 'Saved poses' ], [ 'phoneme', 'Phoneme targets' ], [ 'fit', 'Fitted targets' ], [ 'said', 'Said as in a recording' ] ] );
	assert.equal( fitDescription( { kind: 'surface', report: null } ), 'surface fit' );

} );

test( 'a phoneme target says what its palatogram was fitted to', () => {

	assert.equal( epgBasisText( 'real EPG' ), '; palatogram fitted to real EPG' );
	assert.equal( epgBasisText( 'published descriptions' ), '; palatogram estimated from published descriptions' );
	assert.equal( epgBasisText( 'not fitted' ), '; palatogram not fitted' );
	assert.equal( epgBasisText( undefined ), '' );

} );
