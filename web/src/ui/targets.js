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

import { api as pageApi } from '../api.js';

/** Saved poses (GET /poses): each is one static frame, its synthetic EPG from POST /epg/contacts. */
export class SavedPoseTargets {

	/** @param {{ api?: object }} options the HTTP client the poses are read through */
	constructor( { api = pageApi } = {} ) {

		this.kind = 'pose';
		this.title = 'Saved poses';
		this.api = api;

	}

	async list() {

		const body = await this.api.get( 'poses?limit=1000' );
		return body.poses.map( ( pose ) => ( { id: String( pose.id ), label: pose.name, description: pose.description ?? '' } ) );

	}

	async frames( id ) {

		const pose = await this.api.get( `poses/${ encodeURIComponent( id ) }` );
		const epg = await this.api.post( 'epg/contacts', { params: pose.params } );
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
