// Keeping a child's attempts as sound (web/src/ui/practice/PracticeAudio.js), through the page's
// HTTP client against a stand-in fetch: sound is sent only after a clear "on" from the child's
// switch, as a 16 kHz 16-bit WAV under audio/wav; anything else sends nothing.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { createApi } from '../../web/src/api.js';
import { parseWav } from '../../web/src/core/listen/wav.js';
import { MAX_RECORDING_S, PracticeAudio, uploadFailureMessage } from '../../web/src/ui/practice/PracticeAudio.js';
import { sine } from './support/listenSignals.js';

/** A client whose fetch answers by `route( method, url )` -> [ status, body ] and records every request. */
function server( route ) {

	const requests = [];
	const api = createApi( { tokenSource: () => 'child-token', fetchImpl: async ( url, init ) => {

		requests.push( { url, method: init.method, headers: init.headers, body: init.body } );
		const [ status, body ] = route( init.method, url );
		return { ok: status < 300, status, statusText: '', json: async () => body };

	} } );
	return { api, requests };

}

const switchAnswer = ( enabled ) => ( { child_id: 5, enabled, set_by: enabled ? 3 : null, set_by_name: enabled ? 'Dr Ames' : null, set_at: null, history: [] } );
/** Half a second of a 440 Hz tone at 48 kHz, as the microphone gives it. */
const attempt = () => ( { samples: sine( 24000, 48000, 440, 0.3 ), sampleRate: 48000 } );
const carriesSound = ( request ) => request.body instanceof Uint8Array || request.body instanceof ArrayBuffer || request.method === 'PUT';

test( 'with recording on, an attempt is PUT as a 16 kHz mono WAV under audio/wav, with the child\'s token', async () => {

	const { api, requests } = server( ( method ) => ( method === 'GET' ? [ 200, switchAnswer( true ) ] : [ 201, { practice_id: 41, sample_rate: 16000, duration_s: 0.5 } ] ) );
	const audio = new PracticeAudio( { api } );
	assert.equal( await audio.read( 5 ), true );
	assert.equal( requests[ 0 ].url, '/api/v1/children/5/audio-recording' );
	const answer = await audio.keep( 41, attempt() );
	assert.equal( answer.practice_id, 41 );
	const put = requests[ 1 ];
	assert.deepEqual( [ put.method, put.url, put.headers[ 'Content-Type' ], put.headers.Authorization ], [ 'PUT', '/api/v1/practice/41/audio', 'audio/wav', 'Bearer child-token' ] );
	const wav = parseWav( put.body );
	assert.deepEqual( [ wav.sampleRate, wav.channels, wav.bitsPerSample ], [ 16000, 1, 16 ] );
	assert.equal( wav.samples.length, 8000, 'just the attempt: half a second' );
	assert.deepEqual( audio.report(), { enabled: true, kept: [ 41 ], failed: [], pending: 0 } );

} );

test( 'with recording off, unreadable or unclear, no request carries sound', async () => {

	for ( const [ what, route ] of [
		[ 'off', () => [ 200, switchAnswer( false ) ] ],
		[ 'a refusal', () => [ 403, { detail: 'not your class' } ] ],
		[ 'an answer without the field', () => [ 200, { child_id: 5 } ] ],
		[ 'a truthy string', () => [ 200, { ...switchAnswer( false ), enabled: 'yes' } ] ],
	] ) {

		const { api, requests } = server( route );
		const audio = new PracticeAudio( { api } );
		const warn = console.warn;
		console.warn = () => {};
		try {

			assert.equal( await audio.read( 5 ), false, what );

		} finally {

			console.warn = warn;

		}

		assert.equal( await audio.keep( 41, attempt() ), null, what );
		assert.deepEqual( requests.filter( carriesSound ), [], `${ what }: nothing sent` );

	}

	const { api, requests } = server( () => [ 200, switchAnswer( true ) ] );
	const never = new PracticeAudio( { api } );
	assert.equal( await never.keep( 41, attempt() ), null, 'never read: off' );
	assert.equal( requests.length, 0 );

} );

test( 'an attempt without sound sends nothing, and a long one is cut to what the server keeps', async () => {

	const { api, requests } = server( ( method ) => ( method === 'GET' ? [ 200, switchAnswer( true ) ] : [ 201, {} ] ) );
	const audio = new PracticeAudio( { api } );
	await audio.read( 5 );
	assert.equal( await audio.keep( 41, { samples: new Float32Array( 0 ), sampleRate: 48000 } ), null );
	assert.equal( await audio.keep( 41, null ), null );
	await audio.keep( 42, { samples: new Float32Array( 8000 * ( MAX_RECORDING_S + 2 ) ), sampleRate: 8000 } );
	assert.equal( parseWav( requests.at( - 1 ).body ).samples.length, 16000 * MAX_RECORDING_S );

} );

test( 'a refusal is an error with plain words; a 409 (switched off meanwhile) turns it off here too', async () => {

	let status = 409;
	const { api } = server( ( method ) => ( method === 'GET' ? [ 200, switchAnswer( true ) ] : [ status, { detail: 'recording is off for this child' } ] ) );
	const audio = new PracticeAudio( { api } );
	await audio.read( 5 );
	const refused = await audio.keep( 41, attempt() ).catch( ( error ) => error );
	assert.equal( refused.status, 409 );
	assert.match( uploadFailureMessage( refused ), /switched off.*Your try is saved/ );
	assert.equal( audio.enabled, false );
	assert.equal( await audio.keep( 42, attempt() ), null, 'nothing more is sent' );
	await audio.read( 5 );
	status = 500;
	const failed = await audio.keep( 43, attempt() ).catch( ( error ) => error );
	assert.equal( failed.status, 500 );
	assert.match( uploadFailureMessage( failed ), /could not be kept.*Your try is saved/ );
	assert.equal( audio.enabled, true, 'a server failure does not change the switch' );
	assert.deepEqual( audio.report().failed, [ 41, 43 ] );

} );

test( 'signing out forgets the switch, and a read overtaken by another does not count', async () => {

	const answers = [];
	const api = { get: () => new Promise( ( resolve ) => answers.push( resolve ) ) };
	const audio = new PracticeAudio( { api } );
	const first = audio.read( 5 );
	audio.reset(); // signed out while the read was on its way
	answers[ 0 ]( switchAnswer( true ) );
	assert.equal( await first, false );
	assert.equal( audio.enabled, false );
	const older = audio.read( 5 );
	const newer = audio.read( 5 );
	answers[ 2 ]( switchAnswer( false ) );
	answers[ 1 ]( switchAnswer( true ) );
	await Promise.all( [ older, newer ] );
	assert.equal( audio.enabled, false, 'the newest answer counts' );

} );
