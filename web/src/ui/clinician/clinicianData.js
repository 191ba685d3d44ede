// Where the clinician view's data come from, all through the HTTP client: the recordings and the
// targets to choose from (targets.js sources), a recording's frames, a target's frames, and the
// comparison of the two (POST /epg/recordings/{id}/compare). Answers become the typed frames and
// index tracks the view draws (clinicianFrames.js). The view itself fetches nothing; tests hand
// this a fake client.

import { api as pageApi } from '../../api.js';
import { codesFromRows, framesFromRows, indexTracks } from './clinicianFrames.js';
import { recordingTitle } from './clinicianText.js';
import { parseTargetName, targetSources } from '../shared/targets.js';

/** How a recording is listed: its title (word, speaker; else its name), frame count and rate. */
export function recordingLabel( recording ) {

	const rate = recording.frame_rate_hz ? `, ${ Math.round( recording.frame_rate_hz ) } Hz` : '';
	return `${ recordingTitle( recording ) } (${ recording.n_frames } frames${ rate })`;

}

export class ClinicianData {

	/**
	 * @param {{ api?: object, sources?: object[] }} options the HTTP client, and the target sources
	 *   (targets.js; made on the same client by default)
	 */
	constructor( { api = pageApi, sources = targetSources( { api } ) } = {} ) {

		this.api = api;
		this.sources = sources;

	}

	/**
	 * What there is to choose from:
	 * { recordings: [{ value, label }], groups: [{ title, targets: [{ value, label }] }], empty }
	 * where a target's value is its name ('pose:3') and `empty` says there is nothing at all.
	 */
	async choices() {

		// A source that cannot be listed (e.g. phoneme targets not built: 503) leaves its group
		// empty, with the reason, instead of hiding every other target.
		const [ recordings, ...targetLists ] = await Promise.all( [
			this.api.get( 'epg/recordings?limit=1000' ),
			...this.sources.map( ( source ) => source.list().catch( ( error ) => error ) ),
		] );
		const groups = this.sources.map( ( source, k ) => {

			const list = targetLists[ k ];
			const group = {
				title: source.title,
				targets: list instanceof Error ? [] : list.map( ( target ) => ( { value: `${ source.kind }:${ target.id }`, label: target.label } ) ),
			};
			if ( list instanceof Error ) group.error = list.message;
			return group;

		} );
		return {
			recordings: recordings.recordings.map( ( r ) => ( { value: String( r.id ), label: recordingLabel( r ) } ) ),
			groups,
			empty: ! recordings.total && groups.every( ( group ) => group.targets.length === 0 ),
		};

	}

	/**
	 * A recording ready to show: { id, name, title (clinicianText.recordingTitle), frameRateHz, t_s: Float64Array, frames: Uint8Array
	 * (64 cells per frame), count, indices: { name: Float64Array } }.
	 */
	async recording( id ) {

		const body = await this.api.get( `epg/recordings/${ encodeURIComponent( id ) }` );
		const frames = framesFromRows( body.frames );
		return {
			id: body.id, name: body.name, title: recordingTitle( body ), frameRateHz: body.frame_rate_hz, t_s: Float64Array.from( body.t_s ),
			frames, count: body.n_frames, indices: indexTracks( frames, body.n_frames ),
		};

	}

	/**
	 * A target ready to show, by name ('pose:3'): what its source gives ({ label, rows, t_s,
	 * params, reference }) with its name, frames (64 cells per frame), count and index tracks.
	 * Rejects when no source has that kind.
	 */
	async target( name ) {

		const parsed = parseTargetName( name );
		const source = this.sources.find( ( s ) => s.kind === parsed?.kind );
		if ( ! source ) throw new Error( `There is no target "${ name }"` );
		const target = await source.frames( parsed.id );
		const frames = framesFromRows( target.rows );
		return { name, ...target, frames, count: target.rows.length, indices: indexTracks( frames, target.rows.length ) };

	}

	/**
	 * The compare API's agreement and index differences of a recording and a target (as target()
	 * and recording() give them), with the codes as 64 cells per frame in `codeFrames`.
	 */
	async compare( recording, target ) {

		const reference = { ...target.reference };
		if ( target.count > 1 && target.t_s ) reference.t_s = target.t_s;
		const body = await this.api.post( `epg/recordings/${ encodeURIComponent( recording.id ) }/compare`, { reference } );
		return { ...body, codeFrames: codesFromRows( body.codes ) };

	}

}
