// The workbench's controls without a browser: saving a pose over HTTP (a fake fetch), the error
// messages a teacher sees, and how sliders are labelled, stepped and read out.
import { test } from 'node:test';
import assert from 'node:assert/strict';

import { ApiError, createApi } from '../../web/src/api.js';
import { savePose } from '../../web/src/ui/workbench/PoseBox.js';
import { formatValue, humanise, shortLabel, sliderStep } from '../../web/src/ui/workbench/ParameterPanel.js';

/** A fetch that records its requests and answers with `status` and `body`. */
function fakeFetch( status, body ) {

	const requests = [];
	const fetchImpl = async ( url, init ) => {

		requests.push( { url, init, body: JSON.parse( init.body ) } );
		return { ok: status >= 200 && status < 300, status, statusText: 'status text', json: async () => body };

	};

	return { api: createApi( { fetchImpl } ), requests };

}

test( 'saving a pose posts its trimmed name and every parameter to /api/v1/poses', async () => {

	const { api, requests } = fakeFetch( 201, { id: 1, name: 'alveolar stop', params: { tip_height: 6 } } );
	const pose = await savePose( '  alveolar stop ', { tip_height: 6, jaw_opening: 2 }, { api } );
	assert.equal( pose.id, 1 );
	assert.equal( requests.length, 1 );
	assert.equal( requests[ 0 ].url, '/api/v1/poses' );
	assert.equal( requests[ 0 ].init.method, 'POST' );
	assert.equal( requests[ 0 ].init.headers[ 'Content-Type' ], 'application/json' );
	assert.deepEqual( requests[ 0 ].body, { name: 'alveolar stop', params: { tip_height: 6, jaw_opening: 2 } } );

} );

test( 'a duplicate pose name is explained with the name', async () => {

	const { api } = fakeFetch( 409, { detail: "field name: a pose named 'ah' already exists" } );
	await assert.rejects( savePose( 'ah', {}, { api } ), ( error ) => error instanceof ApiError && error.status === 409 &&
		error.message === 'A pose named "ah" already exists. Choose another name.' );

} );

test( 'a refused value shows where and what in words, from the validation details', async () => {

	const detail = [ { loc: [ 'body', 'params', 'tip_height' ], msg: 'Input should be a finite number', type: 'finite_number' } ];
	const { api } = fakeFetch( 422, { detail } );
	await assert.rejects( savePose( 'x', { tip_height: 1 }, { api } ), { message: 'Tip height: input should be a finite number. The pose was not saved.' } );

} );

test( 'a pose without a name is refused before anything is sent', async () => {

	const { api, requests } = fakeFetch( 201, {} );
	await assert.rejects( savePose( '   ', {}, { api } ), { message: 'Give the pose a name first.' } );
	assert.equal( requests.length, 0 );

} );

test( 'an unreachable server is said so', async () => {

	const fetchImpl = async () => {

		throw new TypeError( 'Failed to fetch' );

	};

	await assert.rejects( savePose( 'a', {}, { api: createApi( { fetchImpl } ) } ), { message: 'Could not reach the server, so the pose was not saved. Check the connection and save again.' } );

} );

test( 'sliders are named in words, without repeating their group inside it', () => {

	assert.equal( humanise( 'front_groove_depth' ), 'Front groove depth' );
	assert.equal( shortLabel( 'front_groove_depth', 'tongue coronal front' ), 'Groove depth' );
	assert.equal( shortLabel( 'back_dorsum_height', 'tongue sagittal' ), 'Back dorsum height' );
	assert.equal( shortLabel( 'jaw_opening', 'jaw' ), 'Jaw opening' );

} );

test( 'a slider steps by about a 200th of its range, a round number', () => {

	assert.equal( sliderStep( { min: - 4, max: 10 } ), 0.05 );
	assert.equal( sliderStep( { min: 0, max: 25 } ), 0.1 );
	assert.equal( sliderStep( { min: 0, max: 50 } ), 0.2 );
	assert.equal( sliderStep( { min: - 3, max: 3 } ), 0.02 );
	assert.equal( sliderStep( { min: 1, max: 1 } ), 1 );

} );

test( 'values read out with their unit, a true minus sign and no float noise', () => {

	assert.equal( formatValue( Math.fround( 2.3 ), 'mm' ), '2.3 mm' );
	assert.equal( formatValue( 2.25, 'mm' ), '2.25 mm' );
	assert.equal( formatValue( - 1.5, 'mm' ), '\u22121.5 mm' );
	assert.equal( formatValue( - 0.001, 'mm' ), '0.0 mm' );
	assert.equal( formatValue( 12, 'deg' ), '12.0°' );
	assert.equal( formatValue( 0.5, '' ), '0.5' );
	assert.equal( formatValue( 0.75, 'ratio' ), '0.75' );

} );
