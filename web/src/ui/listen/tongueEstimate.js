// The listening page's estimate of the learner's tongue from their voice (core/listen/inversion.js
// over the built codebook): live, hop by hop as they speak, each hop given the one before's pose;
// and for a finished attempt, the cheapest path through all its hops, averaged.
//
// With a target vowel the search keeps to the vowels' entries; with none it may also reach /ɹ/
// and /l/. A hop without a voice or without F1 to F3 gives nothing, and the live estimate lapses
// LIVE_HOLD_S after the last hop that gave one, so that silence, noise or a fricative show no
// tongue.

import { anchorEntry, codebookPose, estimableFormants, groupScale, invertFrame, invertTrack, keepTo, readCodebook } from '../../core/listen/inversion.js';

/** Where the build puts the codebook (pipeline/inversion_codebook.py). */
export const CODEBOOK_URL = '/assets/build/inversion-codebook.json';
/** The vowels' anchors (IPA): the entries searched when the learner aims at a vowel. */
export const VOWEL_ANCHORS = Object.freeze( [ 'i', 'ɪ', 'ɛ', 'æ', 'ʌ', 'ɑ', 'ɔ', 'ʊ', 'u', 'ɝ' ] );
/** Seconds a live estimate stays after the last hop that gave one (a consonant's gap). */
export const LIVE_HOLD_S = 0.25;

export class TongueEstimator {

	/** @param {object} document the inversion-codebook.json document */
	constructor( document ) {

		this.full = readCodebook( document );
		this.vowels = keepTo( this.full, VOWEL_ANCHORS.filter( ( ipa ) => this.full.anchors.includes( ipa ) ) );
		this.scratch = new Float64Array( this.full.count );
		this.reset();

	}

	/** Forget the live estimate (a new attempt, another target or group). */
	reset() {

		this.seenHops = null;
		this.seenT = - Infinity;
		this.previous = null;
		this.lastEstimate = null;

	}

	codebook( target ) {

		return target ? this.vowels : this.full;

	}

	/**
	 * The live estimate after the hops so far (the page's array of listening hops, oldest first,
	 * growing at the end and trimmed at the start): { params, entry, t } of the newest hop that
	 * gave one (the same object while the entry stays), null once LIVE_HOLD_S has passed without
	 * one.
	 */
	live( hops, { group, target } ) {

		const key = `${ group }|${ target }`;
		const newest = hops.at( - 1 )?.t ?? - Infinity;
		if ( hops !== this.seenHops || key !== this.key || newest < this.seenT ) {

			this.reset();
			this.seenHops = hops;
			this.key = key;

		}

		const codebook = this.codebook( target );
		const scale = groupScale( codebook, group );
		let first = hops.length;
		while ( first > 0 && hops[ first - 1 ].t > this.seenT ) first --;
		for ( const hop of hops.slice( first ) ) {

			this.seenT = hop.t;
			const entry = invertFrame( estimableFormants( hop ), codebook, scale, this.previous, this.scratch );
			if ( entry === null ) continue;
			this.previous = entry;
			// The same entry keeps its object, so the page sees nothing new to draw.
			if ( this.lastEstimate?.entry === entry ) this.lastEstimate.t = hop.t;
			else this.lastEstimate = { params: codebookPose( codebook, entry ), entry, t: hop.t };

		}

		return this.lastEstimate && newest - this.lastEstimate.t <= LIVE_HOLD_S ? this.lastEstimate : null;

	}

	/**
	 * A finished attempt's estimate: the mean pose over the hops the path through them estimated,
	 * { params, frames }, or null when none could be.
	 */
	attempt( hops, { group, target } ) {

		const codebook = this.codebook( target );
		const path = invertTrack( hops.map( estimableFormants ), codebook, groupScale( codebook, group ) );
		const entries = path.filter( ( entry ) => entry !== null );
		if ( ! entries.length ) return null;
		const params = { ...codebook.fixed };
		codebook.parameters.forEach( ( name, p ) => {

			let sum = 0;
			for ( const entry of entries ) sum += codebook.values[ entry * codebook.size + p ];
			params[ name ] = sum / entries.length;

		} );
		return { params, frames: entries.length };

	}

	/** The anchors (IPA) nearest a pose, nearest first: its parameters in their spread. */
	nearestAnchors( params, count = 2 ) {

		const { anchors, parameters, size, scaled, spread } = this.full;
		return anchors.map( ( ipa ) => {

			const entry = anchorEntry( this.full, ipa );
			let sum = 0;
			for ( let p = 0; p < size; p ++ ) {

				const d = ( params[ parameters[ p ] ] ?? 0 ) / spread[ p ] - scaled[ entry * size + p ];
				sum += d * d;

			}

			return { ipa, distance: sum / size };

		} ).sort( ( a, b ) => a.distance - b.distance ).slice( 0, count ).map( ( { ipa } ) => ipa );

	}

}
