// Playing the kept sound of a child's go, in the clinician's practice table. The WAV is fetched
// with the page's token (GET /practice/{id}/audio; an <audio src> could not send it) and shown
// in an <audio controls> element through an object URL (the server's Content-Security-Policy
// allows blob: media for this).

import { api as pageApi } from '../../api.js';
import { h } from '../shared/dom.js';

export class AttemptSound {

	/** @param {{ api?: object }} options the HTTP client the sounds are fetched through */
	constructor( { api = pageApi } = {} ) {

		this.api = api;
		this.urls = [];
		this.state = { opened: [], playing: null, via: null, error: null };

	}

	/** What window.glasshead.clinicianChild.sound reports. */
	report() {

		return { ...this.state, opened: [ ...this.state.opened ] };

	}

	/** The Play button of go `recordId` (`when` names it for a screen reader); it becomes the player. */
	button( recordId, when ) {

		const cell = h( 'span', { className: 'cc-sound' } );
		const play = h( 'button', { type: 'button', className: 'cc-play', 'aria-label': `Play the go of ${ when }`, onClick: () => this.open( recordId, cell, when ) }, '▶ Play' );
		cell.append( play );
		return cell;

	}

	/** Fetch the sound, put its player in `cell`, and play it. */
	async open( recordId, cell, when ) {

		this.state.error = null;
		let blob;
		try {

			blob = ( await this.api.exchange( 'GET', `practice/${ recordId }/audio`, { read: 'blob' } ) ).body;

		} catch ( error ) {

			this.state.error = error.message;
			cell.replaceChildren( h( 'span', { className: 'cc-sound-error', role: 'alert' }, error.status === 404 ? 'The sound is no longer kept.' : `The sound could not be loaded: ${ error.message }` ) );
			return;

		}

		this.state.opened.push( recordId );
		const url = URL.createObjectURL( blob );
		this.urls.push( url );
		const element = h( 'audio', { controls: '', preload: 'auto', src: url, 'aria-label': `The go of ${ when }` } );
		cell.replaceChildren( element );
		try {

			await element.play();
			this.state = { ...this.state, playing: recordId, via: 'element' };
			element.addEventListener( 'ended', () => this.ended( recordId ), { once: true } );

		} catch ( error ) {

			// NotAllowedError: the browser wants a press on the player itself, which is there.
			if ( error?.name !== 'NotAllowedError' ) {

				this.state.error = error.message;
				cell.append( h( 'span', { className: 'cc-sound-error', role: 'alert' }, `The sound could not be played: ${ error.message }` ) );

			}

		}

	}

	ended( recordId ) {

		if ( this.state.playing === recordId ) this.state.playing = null;

	}

	/** Let go of the sounds (another child chosen, the view left). */
	dispose() {

		for ( const url of this.urls ) URL.revokeObjectURL( url );
		this.urls = [];
		this.state = { opened: [], playing: null, via: null, error: null };

	}

}
