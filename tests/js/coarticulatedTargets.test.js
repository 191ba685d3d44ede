// The clinician's targets that say a recording's own phones (web/src/ui/shared/targets.js,
// CoarticulatedTargets) and the per-phone line under the agreement card (clinicianText.js), with a
// fake HTTP client.
import { test } from 'node:test';
import assert from 'node:assert/strict';

import { createApi } from '../../web/src/api.js';
import { CoarticulatedTargets } from '../../web/src/ui/shared/targets.js';
import { phoneScoresText } from '../../web/src/ui/clinician/clinicianText.js';

const ROWS = [ '00000000', '11000011', '10000001', '10000001', '10000001', '10000001', '10000001', '10000001' ];
const SAID = {
	recording_id: 4, label: '/s/ /k/ said as in sp1bescan s->k', boundary_source: 'centre of gravity',
	phones: [ { symbol: 'S', ipa: 's', start_s: 0, end_s: 0.15 }, { symbol: 'K', ipa: 'k', start_s: 0.15, end_s: 0.265 } ],
	t_s: [ 0, 0.005, 0.2 ], frames: [ ROWS, ROWS, ROWS ],
};

function fakeApi() {

	const requests = [];
	const api = createApi( { fetchImpl: async ( url, init ) => {

		const key = `${ init.method } ${ url.replace( '/api/v1/', '' ) }`;
		requests.push( { key, body: init.body === undefined ? undefined : JSON.parse( init.body ) } );
		const routes = {
			'GET epg/recordings?limit=1000': [ 200, { total: 2, recordings: [
				{ id: 4, name: 'sp1bescan s->k', meta: { label: 's->k', word: 'bescan' } },
				{ id: 5, name: 'my take', meta: {} },
			] } ],
			'POST epg/recordings/4/coarticulated': [ 200, SAID ],
		};
		const [ status, body ] = routes[ key ] ?? [ 404, { detail: `no route ${ key }` } ];
		return { ok: status < 300, status, statusText: '', json: async () => body };

	} } );
	return { api, requests };

}

test( 'labelled recordings are listed to be said by the head; one without a label is not', async () => {

	const source = new CoarticulatedTargets( { api: fakeApi().api } );
	assert.deepEqual( await source.list(), [ { id: '4', label: 'sp1bescan s→k, said by the head', description: 'its own phones, coarticulated on its timing' } ] );

} );

test( 'the target is every frame with its time, and the compare reference carries the phones', async () => {

	const { api, requests } = fakeApi();
	const target = await new CoarticulatedTargets( { api } ).frames( '4' );
	assert.deepEqual( requests.map( ( r ) => [ r.key, r.body ] ), [ [ 'POST epg/recordings/4/coarticulated', {} ] ] );
	assert.equal( target.rows.length, 3 );
	assert.deepEqual( target.t_s, [ 0, 0.005, 0.2 ] );
	assert.equal( target.params, null );
	assert.deepEqual( target.reference, {
		label: SAID.label, frames: SAID.frames, t_s: SAID.t_s,
		phones: [ { symbol: 'S', ipa: 's', start_s: 0, end_s: 0.15 }, { symbol: 'K', ipa: 'k', start_s: 0.15, end_s: 0.265 } ],
	} );

} );

test( 'the per-phone line gives kappa per phone and over the phones, and nothing without phones', () => {

	const comparison = {
		phones: [ { symbol: 'S', ipa: 's', frames: 30, mean_kappa: 0.4712 }, { symbol: 'K', frames: 22, mean_kappa: - 0.031 } ],
		summary: { phones: { mean_kappa: 0.22 } },
	};
	assert.equal( phoneScoresText( comparison ), 'Per phone: /s/ κ 0.47 (30 frames) · /K/ κ −0.03 (22 frames); mean over the phones κ 0.22' );
	assert.equal( phoneScoresText( { phones: null, summary: {} } ), null );
	assert.equal( phoneScoresText( null ), null );

} );
