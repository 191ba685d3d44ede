// Playing the kept sound of a child's go, in the clinician's practice table. The WAV is fetched
// with the page's token (GET /practice/{id}/audio; an <audio src> could not send it) and shown
// in an <audio controls> element through an object URL (the server's Content-Security-Policy
// allows blob: media for this). A Delete beside it ends the keeping of that one sound (DELETE
// /practice/{id}/audio), after a second press.

import { api as pageApi } from '../../api.js';
import { h } from '../shared/dom.js';

export class AttemptSound {

	/** @param {{ api?: object }} options the HTTP client the sounds are fetched through */
	constructor( { api = pageApi } = {} ) {

		this.api = api;
		this.urls = [];
		this.state = { opened: [], playing: null, via: null, error: null, deleted: [] };

	}

	/** What window.glasshead.clinicianChild.sound reports. */
	report() {

		return { ...this.state, opened: [ ...this.state.opened ], deleted: [ ...this.state.deleted ] };

	}

	/**
	 * The Play button of go `recordId` (`when` names it for a screen reader), which becomes the
	 * player, and a Delete button beside it that asks once more before the sound goes for good.
	 */
	button( recordId, when ) {

		const cell = h( 'span', { className: 'cc-sound' } );
		const player = h( 'span', { className: 'cc-sound' } );
		const play = h( 'button', { type: 'button', className: 'cc-play', 'aria-label': `Play the go of ${ when }`, onClick: () => this.open( recordId, player, when ) }, '▶ Play' );
		player.append( play );
		cell.append( player, this.deleteControl( recordId, when, cell ) );
		return cell;

	}

	/** "Delete" then "Delete for good? Yes / Keep it": a kept sound goes only on a second press. */
	deleteControl( recordId, when, cell ) {

		const control = h( 'span', { className: 'cc-sound-delete' } );
		const ask = () => control.replaceChildren(
			h( 'span', {}, 'Delete this sound for good?' ),
			h( 'button', { type: 'button', 'aria-label': `Yes, delete the sound of the go of ${ when }`, onClick: () => this.remove( recordId, cell ) }, 'Yes, delete' ),
			h( 'button', { type: 'button', 'aria-label': `Keep the sound of the go of ${ when }`, onClick: () => control.replaceChildren( first() ) }, 'Keep it' ) );
		const first = () => h( 'button', { type: 'button', className: 'cc-delete', 'aria-label': `Delete the sound of the go of ${ when }`, onClick: ask }, 'Delete' );
		control.append( first() );
		return control;

	}

	/** DELETE the sound; the cell then says it is gone (or why it could not go). */
	async remove( recordId, cell ) {

		this.state.error = null;
		try {

			await this.api.exchange( 'DELETE', `practice/${ recordId }/audio` );

		} catch ( error ) {

			if ( error.status !== 404 ) {

				this.state.error = error.message;
				cell.append( h( 'span', { className: 'cc-sound-error', role: 'alert' }, `The sound could not be deleted: ${ error.message }` ) );
				return;

			}

		}

		this.state.deleted.push( recordId );
		cell.replaceChildren( h( 'span', { role: 'status' }, 'Sound deleted.' ) );

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
		this.state = { opened: [], playing: null, via: null, error: null, deleted: [] };

	}

}
