// Where the clinician's targets come from. A target is what a client's EPG is compared with: today
// a saved pose (a named parameter set from the workbench) shown as its synthetic EPG; later a
// fitted phoneme target. The clinician view only ever talks to a TargetSource:
//
//   kind                   short name used in ids ('pose'; a phoneme source would be 'phoneme')
//   title                  what the chooser calls the group ('Saved poses')
//   list()                 -> Promise<[{ id, label, description }]>, id unique within the source
//   frames( id )           -> Promise<{ label, rows: string[][], t_s: number[] | null,
//                              reference: object }>: the target's EPG frames (8 row strings each,
//                              R1 first), their times (null for one static frame), and what to
//                              send as the `reference` of POST /epg/recordings/{id}/compare
//
// Targets are named `${kind}:${id}` in the view's URL (#/clinician?target=pose:3), so a new
// source needs no change to the view: add an object with these members to TARGET_SOURCES.

import { API_BASE, ApiError, fetchJson } from '../api.js';

/** POST JSON under the API base and parse the answer; rejects with an ApiError naming the request. */
export async function postJson( path, body, { fetchImpl = globalThis.fetch } = {} ) {

	const url = path.startsWith( API_BASE ) ? path : API_BASE + path;
	let response;
	try {

		response = await fetchImpl( url, { method: 'POST', headers: { 'Content-Type': 'application/json', Accept: 'application/json' }, body: JSON.stringify( body ) } );

	} catch ( error ) {

		throw new ApiError( `Could not reach the server for ${ url }: ${ error.message }`, { url } );

	}

	const text = await response.text();
	let parsed;
	try {

		parsed = text ? JSON.parse( text ) : null;

	} catch {

		parsed = null;

	}

	if ( ! response.ok ) {

		const detail = typeof parsed?.detail === 'string' ? parsed.detail : text.slice( 0, 300 );
		throw new ApiError( `POST ${ url } failed with HTTP ${ response.status }: ${ detail }`, { url, status: response.status } );

	}

	if ( parsed === null ) throw new ApiError( `POST ${ url } returned no JSON`, { url, status: response.status } );
	return parsed;

}

/** Saved poses (GET /poses): each is one static frame, its synthetic EPG from POST /epg/contacts. */
export class SavedPoseTargets {

	constructor( { fetchImpl = globalThis.fetch } = {} ) {

		this.kind = 'pose';
		this.title = 'Saved poses';
		this.fetchImpl = fetchImpl;

	}

	async list() {

		const body = await fetchJson( '/poses?limit=1000', { fetchImpl: this.fetchImpl } );
		return body.poses.map( ( pose ) => ( { id: String( pose.id ), label: pose.name, description: pose.description ?? '' } ) );

	}

	async frames( id ) {

		const pose = await fetchJson( `/poses/${ encodeURIComponent( id ) }`, { fetchImpl: this.fetchImpl } );
		const epg = await postJson( '/epg/contacts', { params: pose.params }, { fetchImpl: this.fetchImpl } );
		return {
			label: pose.name,
			rows: [ epg.rows ],
			t_s: null,
			params: pose.params,
			reference: { label: pose.name, pose_id: pose.id, frames: [ epg.rows ] },
		};

	}

}

/** Every source of targets, in the order the chooser lists them. */
export function targetSources( options ) {

	return [ new SavedPoseTargets( options ) ];

}

/** Split a target name 'pose:3' into { kind: 'pose', id: '3' } (null when it has no kind). */
export function parseTargetName( name ) {

	const match = /^([a-z][a-z0-9_-]*):(.+)$/.exec( name ?? '' );
	return match ? { kind: match[ 1 ], id: match[ 2 ] } : null;

}
