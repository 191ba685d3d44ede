// Where the clinician's targets come from. A target is what a client's EPG is compared with: today
// a saved pose (a named parameter set from the workbench), a phoneme's articulation target
// (GET /phonemes) or a target fitted to an author's own data (GET /fits), each shown as its
// synthetic EPG. The clinician view only ever talks to a TargetSource:
//
//   kind                   short name used in ids ('pose', 'phoneme', 'fit')
//   title                  what the chooser calls the group ('Saved poses', 'Phoneme targets')
//   list()                 -> Promise<[{ id, label, description }]>, id unique within the source
//   frames( id )           -> Promise<{ label, rows: string[][], t_s: number[] | null,
//                              reference: object }>: the target's EPG frames (8 row strings each,
//                              R1 first), their times (null for one static frame), and what to
//                              send as the `reference` of POST /epg/recordings/{id}/compare
//
// A target may also say a recording's own phones on its timing (CoarticulatedTargets): many frames
// with their times, and the phones, so that the comparison scores each phone's frames.
//
// Targets are named `${kind}:${id}` in the view's URL (#/clinician?target=pose:3), so a new
// source needs no change to the view: add an object with these members to TARGET_SOURCES.

import { api as pageApi } from '../../api.js';
import { loadPhonemeList, loadPhonemeTarget } from './loaders.js';

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

/** What a phoneme target's palatogram was fitted to, as a clause ('' when the server does not say). */
export function epgBasisText( basis ) {

	if ( basis === 'real EPG' ) return '; palatogram fitted to real EPG';
	if ( basis === 'published descriptions' ) return '; palatogram estimated from published descriptions';
	if ( basis === 'not fitted' ) return '; palatogram not fitted';
	return '';

}

/** How a phoneme is listed: its IPA in slashes, its ARPAbet symbol and an example word. */
export function phonemeLabel( phoneme ) {

	const example = phoneme.examples?.length ? ` as in "${ phoneme.examples[ 0 ] }"` : '';
	return `/${ phoneme.ipa }/ ${ phoneme.arpabet }${ example }`;

}

/**
 * The phoneme targets (GET /phonemes, docs/targets.md): each one static frame, the synthetic EPG
 * the build computed for its parameters (the same contacts the browser computes for them). Ids are
 * ARPAbet symbols ('phoneme:T').
 */
export class PhonemeTargets {

	/** @param {{ api?: object }} options the HTTP client the targets are read through */
	constructor( { api = pageApi } = {} ) {

		this.kind = 'phoneme';
		this.title = 'Phoneme targets';
		this.api = api;

	}

	async list() {

		const body = await loadPhonemeList( { api: this.api } );
		return body.phonemes.map( ( phoneme ) => ( {
			id: phoneme.arpabet,
			label: phonemeLabel( phoneme ),
			description: `${ phoneme.source?.shapes?.length ? `fitted to ${ phoneme.source.shapes.join( ', ' ) }` : 'from phonetic reasoning' }${ epgBasisText( phoneme.epg_basis ) }`,
		} ) );

	}

	async frames( id ) {

		const target = await loadPhonemeTarget( id, { api: this.api } );
		const label = phonemeLabel( target );
		return {
			label,
			rows: [ target.epg.rows ],
			t_s: null,
			params: target.params,
			reference: { label, frames: [ target.epg.rows ] },
		};

	}

}

const agreementWords = ( agreement ) => `EPG agreement ${ Math.round( 100 * agreement ) } %`;
/** Words for a part's error in a report's `terms` (docs/fits.md). */
const TERM_WORDS = {
	contour: ( term ) => `contour ${ term.rms_mm.toFixed( 2 ) } mm RMS`,
	epg: ( term ) => agreementWords( term.agreement ),
	ema: ( term ) => `sensors ${ term.rms_mm.toFixed( 2 ) } mm RMS`,
};

/**
 * How well a finished fit matches what it was given, in words: each measurement's error for a
 * fit with `terms`, else the outline's RMS and the EPG agreement.
 */
export function fitErrorWords( report ) {

	if ( ! report ) return '';
	if ( report.terms ) return Object.entries( report.terms ).map( ( [ kind, term ] ) => TERM_WORDS[ kind ]?.( term ) ).filter( Boolean ).join( ', ' );
	const words = [];
	if ( Number.isFinite( report.rms_mm ) ) words.push( `RMS ${ report.rms_mm.toFixed( 2 ) } mm` );
	if ( Number.isFinite( report.agreement ) ) words.push( agreementWords( report.agreement ) );
	return words.join( ', ' );

}

/** How a fitted target is described: what it was fitted to and how closely. */
export function fitDescription( fit ) {

	const error = fitErrorWords( fit.report );
	return `${ fit.kind } fit${ error ? `, ${ error }` : '' }`;

}

/**
 * Targets authors fitted to their own measurements (POST /fits, docs/fits.md): the finished fits
 * (GET /fits?state=done), each one static frame, its synthetic EPG from POST /epg/contacts with the
 * fit's params, as a saved pose's. Ids are the fits' ids ('fit:12').
 */
export class FittedTargets {

	/** @param {{ api?: object }} options the HTTP client the fits are read through */
	constructor( { api = pageApi } = {} ) {

		this.kind = 'fit';
		this.title = 'Fitted targets';
		this.api = api;

	}

	async list() {

		const body = await this.api.get( 'fits?state=done&limit=1000' );
		return body.fits.map( ( fit ) => ( { id: String( fit.id ), label: fit.name, description: fitDescription( fit ) } ) );

	}

	async frames( id ) {

		const fit = await this.api.get( `fits/${ encodeURIComponent( id ) }` );
		if ( fit.state !== 'done' ) throw new Error( `fit ${ fit.id } is ${ fit.state }: it has no target yet` );
		const epg = await this.api.post( 'epg/contacts', { params: fit.params } );
		return {
			label: fit.name,
			rows: [ epg.rows ],
			t_s: null,
			params: fit.params,
			reference: { label: fit.name, frames: [ epg.rows ] },
		};

	}

}

/**
 * The head saying a labelled recording's own phones on its timing (POST
 * /epg/recordings/{id}/coarticulated, docs/epg.md): one frame per frame of the recording, with
 * their times and the phones, so that comparing that recording with it scores each phone's frames
 * against the same phone. Ids are the recordings' ids ('said:12'); recordings without a label
 * ('s->k') are not listed.
 */
export class CoarticulatedTargets {

	/** @param {{ api?: object }} options the HTTP client the recordings are read through */
	constructor( { api = pageApi } = {} ) {

		this.kind = 'said';
		this.title = 'Said as in a recording';
		this.api = api;

	}

	async list() {

		const body = await this.api.get( 'epg/recordings?limit=1000' );
		return body.recordings.filter( ( r ) => typeof r.meta?.label === 'string' && r.meta.label.trim() ).map( ( r ) => ( {
			id: String( r.id ),
			label: `${ r.name.replace( '->', '→' ) }, said by the head`,
			description: 'its own phones, coarticulated on its timing',
		} ) );

	}

	async frames( id ) {

		const said = await this.api.post( `epg/recordings/${ encodeURIComponent( id ) }/coarticulated`, {} );
		return {
			label: said.label,
			rows: said.frames,
			t_s: said.t_s,
			params: null, // many poses: the 3D palate shows static targets only
			reference: { label: said.label, frames: said.frames, t_s: said.t_s, phones: said.phones },
		};

	}

}

/** Every source of targets, in the order the chooser lists them. */
export function targetSources( options ) {

	return [ new SavedPoseTargets( options ), new PhonemeTargets( options ), new FittedTargets( options ), new CoarticulatedTargets( options ) ];

}

/** Split a target name 'pose:3' into { kind: 'pose', id: '3' } (null when it has no kind). */
export function parseTargetName( name ) {

	const match = /^([a-z][a-z0-9_-]*):(.+)$/.exec( name ?? '' );
	return match ? { kind: match[ 1 ], id: match[ 2 ] } : null;

}
