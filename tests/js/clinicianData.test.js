// The clinician view's data source (web/src/ui/clinician/clinicianData.js) on a fake HTTP client: what it
// asks the API for and what it makes of the answers.
import { test } from 'node:test';
import assert from 'node:assert/strict';

import { ApiError, createApi } from '../../web/src/api.js';
import { ClinicianData, recordingLabel } from '../../web/src/ui/clinician/clinicianData.js';
import { EPG_CELLS } from '../../web/src/core/constants.js';
import { near, nearArray } from './support/near.js';

const EMPTY = [ '00000000', '00000000', '00000000', '00000000', '00000000', '00000000', '00000000', '00000000' ];
const FRONT = [ '01111110', '11000011', '00000000', '00000000', '00000000', '00000000', '00000000', '00000000' ];

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
	'GET epg/recordings?limit=1000': () => [ 200, { total: 1, recordings: [ { id: 7, name: 'tata', n_frames: 2, frame_rate_hz: 99.6, meta: { label: 't->a' } } ] } ],
	'GET poses?limit=1000': () => [ 200, { poses: [ { id: 3, name: 'alveolar stop' } ] } ],
	'GET poses/3': () => [ 200, { id: 3, name: 'alveolar stop', params: { tip_height: 6 } } ],
	'POST epg/contacts': () => [ 200, { rows: FRONT } ],
	'GET fits?state=done&limit=1000': () => [ 200, { total: 1, fits: [ { id: 12, name: 'my /t/', kind: 'epg', state: 'done', report: { rms_mm: 1.2 } } ] } ],
	'GET phonemes': () => [ 200, { format_version: 1, count: 1, phonemes: [ { arpabet: 'T', ipa: 't', kind: 'consonant', examples: [ 'tie', 'cat' ], source: { kind: 'fit', shapes: [ 'tt-alveolar-closure(a)' ], rms_mm: 0.9 } } ] } ],
	'GET phonemes/T': () => [ 200, { arpabet: 'T', ipa: 't', kind: 'consonant', examples: [ 'tie', 'cat' ], params: { tip_height: 2, velum_opening: 0 }, epg: { rows: FRONT, indices: {} } } ],
	'GET epg/recordings/7': () => [ 200, { id: 7, name: 'tata', n_frames: 2, frame_rate_hz: 100, t_s: [ 0.5, 0.51 ], frames: [ EMPTY, FRONT ] } ],
	'POST epg/recordings/7/compare': () => [ 200, { agreement: [ 0.8, 1 ], reference_frame: [ 0, 0 ], codes: [ EMPTY, EMPTY ], summary: { mean_agreement: 0.9 } } ],
};

test( 'the choices list the recordings and each source\'s targets by name', async () => {

	const { api } = fakeApi( ROUTES );
	const choices = await new ClinicianData( { api } ).choices();
	assert.deepEqual( choices.recordings, [ { value: '7', label: 'tata (2 frames, 100 Hz)' } ] );
	assert.deepEqual( choices.groups, [
		{ title: 'Saved poses', targets: [ { value: 'pose:3', label: 'alveolar stop' } ] },
		{ title: 'Phoneme targets', targets: [ { value: 'phoneme:T', label: '/t/ T as in "tie"' } ] },
		{ title: 'Fitted targets', targets: [ { value: 'fit:12', label: 'my /t/' } ] },
		{ title: 'Said as in a recording', targets: [ { value: 'said:7', label: 'tata, said by the head' } ] },
	] );
	assert.equal( choices.empty, false );
	assert.equal( recordingLabel( { name: 'x', n_frames: 1 } ), 'x (1 frames)' );

} );

test( 'nothing to choose from says so', async () => {

	const { api } = fakeApi( {
		'GET epg/recordings?limit=1000': () => [ 200, { total: 0, recordings: [] } ],
		'GET poses?limit=1000': () => [ 200, { poses: [] } ],
		'GET phonemes': () => [ 503, { detail: 'asset phoneme_targets (phoneme-targets.json) is missing' } ],
	} );
	const choices = await new ClinicianData( { api } ).choices();
	assert.equal( choices.empty, true );
	assert.match( choices.groups[ 1 ].error, /phoneme-targets.json/, 'the unbuilt phoneme targets say why their group is empty' );

} );

test( 'a recording becomes typed frames, times and index tracks', async () => {

	const { api } = fakeApi( ROUTES );
	const recording = await new ClinicianData( { api } ).recording( '7' );
	assert.equal( recording.count, 2 );
	assert.equal( recording.frameRateHz, 100 );
	assert.ok( recording.t_s instanceof Float64Array );
	assert.equal( recording.frames.length, 2 * EPG_CELLS );
	assert.equal( recording.frames[ EPG_CELLS + 1 ], 1, 'R1 column 2 of the second frame' );
	nearArray( recording.indices.percent, [ 0, 1000 / 62 ], 1e-12, 'percent contact' );

} );

test( 'a saved pose target is its synthetic EPG, and the comparison posts it as the reference', async () => {

	const { api, requests } = fakeApi( ROUTES );
	const data = new ClinicianData( { api } );
	const target = await data.target( 'pose:3' );
	assert.equal( target.name, 'pose:3' );
	assert.equal( target.label, 'alveolar stop' );
	assert.equal( target.count, 1 );
	assert.deepEqual( target.params, { tip_height: 6 } );
	near( target.indices.percent[ 0 ], 1000 / 62, 1e-12, 'percent contact' );
	assert.deepEqual( requests.find( ( r ) => r.key === 'POST epg/contacts' ).body, { params: { tip_height: 6 } } );

	const comparison = await data.compare( await data.recording( '7' ), target );
	assert.deepEqual( requests.at( - 1 ).body, { reference: { label: 'alveolar stop', pose_id: 3, frames: [ FRONT ] } } );
	assert.equal( comparison.codeFrames.length, 2 * EPG_CELLS );
	assert.deepEqual( comparison.agreement, [ 0.8, 1 ] );

} );

test( 'a phoneme target is its built synthetic EPG, posted as the reference', async () => {

	const { api, requests } = fakeApi( ROUTES );
	const data = new ClinicianData( { api } );
	const target = await data.target( 'phoneme:T' );
	assert.equal( target.label, '/t/ T as in "tie"' );
	assert.equal( target.count, 1 );
	assert.deepEqual( target.params, { tip_height: 2, velum_opening: 0 } );
	near( target.indices.percent[ 0 ], 1000 / 62, 1e-12, 'percent contact' );
	assert.ok( ! requests.some( ( r ) => r.key === 'POST epg/contacts' ), 'the built pattern is used as it is' );
	await data.compare( await data.recording( '7' ), target );
	assert.deepEqual( requests.at( - 1 ).body, { reference: { label: '/t/ T as in "tie"', frames: [ FRONT ] } } );

} );

test( 'an unknown target kind is refused, and a server error arrives as an ApiError', async () => {

	const { api } = fakeApi( { 'GET epg/recordings/8': () => [ 404, { detail: 'no recording 8' } ] } );
	const data = new ClinicianData( { api } );
	await assert.rejects( data.target( 'gesture:t' ), /There is no target "gesture:t"/ );
	await assert.rejects( data.recording( '8' ), ( error ) => error instanceof ApiError && error.message === 'GET /api/v1/epg/recordings/8 failed with HTTP 404: no recording 8' );

} );
