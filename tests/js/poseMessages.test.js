// What saving a pose says when it fails, in plain words: the server's real answers (status and
// detail, as POST /api/v1/poses sends them) turned into sentences with no status code or field path.
import { test } from 'node:test';
import assert from 'node:assert/strict';

import { ApiError, createApi } from '../../web/src/api.js';
import { savePose } from '../../web/src/ui/workbench/PoseBox.js';
import { poseSaveMessage } from '../../web/src/ui/workbench/poseMessages.js';

/** The error the client makes of an answer with `status` and `detail`. */
const refused = ( status, detail ) => new ApiError( `POST /api/v1/poses failed with HTTP ${ status }: ${ detail }`, { method: 'POST', url: '/api/v1/poses', status, detail } );

/** A fetch that answers every request with `status` and `{ detail }`. */
function answering( status, detail ) {

	return createApi( { fetchImpl: async () => ( { ok: false, status, statusText: 'status text', json: async () => ( { detail } ) } ) } );

}

test( 'a name that is too long says how long a name can be', () => {

	assert.equal( poseSaveMessage( refused( 422, 'body.name: String should have at most 120 characters' ), 'x'.repeat( 121 ) ),
		'Names can be at most 120 characters. Shorten the name and save again.' );

} );

test( 'saving a 121-character name rejects with the plain sentence, keeping the status on the error', async () => {

	const api = answering( 422, 'body.name: String should have at most 120 characters' );
	await assert.rejects( savePose( 'a'.repeat( 121 ), { tip_height: 1 }, { api } ), ( error ) => error instanceof ApiError && error.status === 422 &&
		error.message === 'Names can be at most 120 characters. Shorten the name and save again.' );

} );

test( 'a value outside its range names the parameter in words, its range and unit', () => {

	assert.equal( poseSaveMessage( refused( 422, 'params.tip_height: 1e+300 is outside [-18, 8] mm' ) ),
		'Tip height must be between -18 and 8 mm; it is 1e+300. The pose was not saved.' );

} );

test( 'an unknown parameter is named, and the pose said not to be saved', () => {

	assert.equal( poseSaveMessage( refused( 422, 'params.lip_width: unknown parameter' ) ), 'The server does not know the parameter "lip_width". The pose was not saved.' );

} );

test( 'validation details as a list are read the same way', () => {

	const detail = [ { loc: [ 'body', 'params', 'tip_height' ], msg: 'Input should be a finite number', type: 'finite_number' } ];
	assert.equal( poseSaveMessage( refused( 422, detail ) ), 'Tip height: input should be a finite number. The pose was not saved.' );

} );

test( 'no message the person reads carries an HTTP status or a body. path', () => {

	const errors = [
		refused( 422, 'body.name: String should have at most 120 characters' ),
		refused( 422, 'body.params: Value error, \'tip height\' is not a parameter name' ),
		refused( 409, 'field name: a pose named \'ah\' already exists' ),
		refused( 413, 'request body too large' ),
		refused( 500, 'Internal Server Error' ),
		refused( 503, 'busy' ),
		new ApiError( 'Could not reach the server for POST /api/v1/poses: Failed to fetch', { method: 'POST', status: null } ),
	];
	for ( const error of errors ) {

		const message = poseSaveMessage( error, 'ah' );
		assert.doesNotMatch( message, /HTTP|body\.|\b[45]\d\d\b/, message );
		assert.ok( message.length > 10, message );

	}

} );

test( 'an error that is not the server\'s keeps its own message', () => {

	assert.equal( poseSaveMessage( new Error( 'Give the pose a name first.' ) ), 'Give the pose a name first.' );

} );
