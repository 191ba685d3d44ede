// "The mouth" on the listening page: the 3D head in profile, cut away, posed at the target vowel's
// phoneme target (ui/shared/ProfileHead.js), with the learner's tongue as a ghost in it; and beside
// it a mid-sagittal drawing of the target's tongue with the learner's (mouthDrawing.js). The
// learner's tongue is estimated from their voice (tongueEstimate.js, core/listen/inversion.js):
// live while they speak, then from the whole attempt. Without a voiced sound there is none.
//
// The panel works from what the page hands it (the group's norms, the target vowel, the hops so
// far, the attempt's summary) and redraws only when one of them, its size or its data changes.

import { h } from '../shared/dom.js';
import { HiDpiCanvas } from '../shared/hidpiCanvas.js';
import { loadArticulationData, loadPhonemeTarget } from '../shared/loaders.js';
import { ProfileHead } from '../shared/ProfileHead.js';
import { drawMouth } from './mouthDrawing.js';
import { TongueProfile } from './tongueProfile.js';
import { CODEBOOK_URL, TongueEstimator } from './tongueEstimate.js';

/** Below this width (CSS pixels) of the displays, the chart and the mouth each take the whole width. */
export const SIDE_BY_SIDE_PX = 1000;
/** Space between the chart and the mouth, and between the head and the drawing, CSS pixels. */
const GAP_PX = 12;
/** The caption above the two views and the notes under them, CSS pixels (their share of the panel's height). */
const WORDS_PX = 96;

/**
 * Where the chart and the mouth go in `width` CSS pixels of displays: side by side, as tall as
 * each other, on a wide screen (a projector); one above the other on a narrow one (a tablet).
 * @returns {{ chart: { width, height }, mouth: { width, height } }}
 */
export function topRowSizes( width ) {

	if ( width >= SIDE_BY_SIDE_PX ) {

		const half = Math.floor( ( width - GAP_PX ) / 2 );
		const height = Math.round( Math.min( half * 0.75, 520 ) );
		return { chart: { width: half, height }, mouth: { width: width - GAP_PX - half, height } };

	}

	const height = Math.round( Math.min( width * 0.75, 520 ) );
	return { chart: { width, height }, mouth: { width, height: Math.round( Math.min( width / 2, 440 ) ) + WORDS_PX } };

}

export class MouthPanel {

	/** @param {{ api: object }} options the HTTP client the head, the rig and the targets are loaded through */
	constructor( { api } ) {

		this.api = api;
		this.stage = h( 'div', { className: 'ls-mouth-head' } );
		// Live, but not a second role="status": the page's status is the listening message.
		this.headMessage = h( 'p', { className: 'ls-mouth-message', 'aria-live': 'polite' } );
		this.headLabel = h( 'p', { className: 'ls-mouth-head-label' } );
		this.drawing = new HiDpiCanvas( { width: 300, height: 300, ariaLabel: 'Your tongue and the target\'s, side view', className: 'ls-canvas ls-mouth-drawing' } );
		this.note = h( 'p', { className: 'ls-mouth-note' } );
		this.blend = h( 'p', { className: 'ls-mouth-blend' } );
		this.element = h( 'figure', { className: 'ls-mouth' }, h( 'figcaption', {}, 'The mouth' ),
			h( 'div', { className: 'ls-mouth-views' }, h( 'div', { className: 'ls-mouth-head-box' }, this.stage, this.headLabel, this.headMessage ), this.drawing.element ),
			this.note, this.blend );
		this.input = { vowels: null, target: null, summary: null, hops: null, group: null };
		/** Phoneme target parameters by vowel code, as they arrive; `targetsSettled` once all have. */
		this.targets = {};
		this.targetsSettled = false;
		this.profile = null;
		this.estimator = null;
		/** What the estimator last gave (findTongue), the estimate shown from it, and its curve. */
		this.found = null;
		this.attempt = null;
		this.curveProfile = null;
		this.estimate = null;
		this.estimateCurve = null;
		this.drawCount = 0;
		this.head = new ProfileHead( this.stage, { api, onChange: () => this.refresh() } );
		this.load();

	}

	async load() {

		try {

			const [ data, codebook ] = await Promise.all( [ loadArticulationData( { api: this.api } ), this.api.get( CODEBOOK_URL ) ] );
			if ( ! this.head ) return;
			this.estimator = new TongueEstimator( codebook );
			this.profile = new TongueProfile( data.definition, data.tables );
			this.head.load( data );

		} catch ( error ) {

			console.warn( `Glasshead: the listening page draws no tongue: ${ error.message }` );
			this.head?.fail( 'failed', `The tongue could not be loaded: ${ error.message }` );

		}

		this.refresh();

	}

	/** The vowels' phoneme targets (GET /phonemes/{arpabet}), once, when the norms first come. */
	async loadTargets( vowels ) {

		this.loadingTargets = true;
		await Promise.allSettled( Object.entries( vowels ).map( async ( [ code, entry ] ) => {

			const target = await loadPhonemeTarget( entry.arpabet ?? code.toUpperCase(), { api: this.api } );
			this.targets[ code ] = target.params;
			if ( code === this.input.target ) this.refresh();

		} ) );
		this.targetsSettled = true;
		this.refresh();

	}

	/**
	 * What the page shows: the group's norms ({ code: entry }), the target vowel's code (null for
	 * none), the group ('child', 'woman', 'man'), the attempt's hops so far (the listening
	 * kernels', oldest first) and its summary (summariseAttempt; null until the attempt ends).
	 * Cheap when nothing changed: the page calls it with every block of sound, and new hops that
	 * leave the estimated tongue as it was draw nothing.
	 */
	update( { vowels, target, summary, hops = null, group = null } ) {

		const input = { vowels: vowels ?? null, target: target || null, summary: summary ?? null, hops, group };
		const same = [ 'vowels', 'target', 'summary', 'group' ].every( ( key ) => input[ key ] === this.input[ key ] );
		this.input = input;
		if ( same && this.findTongue() === this.found ) return;
		if ( input.vowels && ! this.loadingTargets ) this.loadTargets( input.vowels );
		this.refresh();

	}

	/** Pose the head, estimate the learner's tongue, and draw. */
	refresh() {

		if ( ! this.head ) return;
		const { vowels, target, summary } = this.input;
		const targetParams = ( target && this.targets[ target ] ) ?? null;
		this.head.pose( targetParams ?? {} );
		const found = this.findTongue();
		if ( found !== this.found || this.profile !== this.curveProfile ) {

			this.found = found;
			this.curveProfile = this.profile;
			this.estimate = found && { params: found.params, nearest: this.estimator.nearestAnchors( found.params ), live: ! summary, frames: found.frames ?? null };
			this.estimateCurve = this.profile && found ? this.profile.curve( found.params ) : null;
			this.head.ghost( this.estimateCurve );

		}

		this.headMessage.textContent = this.head.status === 'loading' ? 'Loading the head…' : this.head.message;
		this.headMessage.hidden = this.head.status === 'ready';
		this.headLabel.textContent = target ? `Target /${ vowels?.[ target ]?.ipa ?? target }/` : 'No target: the tongue at rest';
		this.headLabel.hidden = this.head.status !== 'ready';
		this.headLabel.dataset.target = String( Boolean( target ) );
		this.note.textContent = this.estimate
			? '“Yours” (blue) is a guess from the sound you made, not a picture of your tongue.'
			: summary && this.estimator
				? 'No tongue could be guessed from that sound: it needs a voiced vowel.'
				: 'Say the vowel: “Yours” will show how your tongue probably moved, guessed from the sound.';
		this.blend.textContent = this.estimate ? `Closest to ${ this.estimate.nearest.map( ( ipa ) => `/${ ipa }/` ).join( ', then ' ) }` : '';
		this.draw( targetParams );

	}

	/**
	 * The learner's tongue as the estimator gives it ({ params, frames? } or null): the finished
	 * attempt's (made once per attempt, target and group), else the live one while hops come.
	 * The same object while the tongue stays the same.
	 */
	findTongue() {

		const { summary, hops, group, target } = this.input;
		if ( ! this.estimator || ! hops?.length || ! group ) return null;
		const options = { group, target };
		if ( ! summary ) return this.estimator.live( hops, options );
		const key = `${ group }|${ target }`;
		if ( this.attempt?.summary !== summary || this.attempt.key !== key ) this.attempt = { summary, key, found: this.estimator.attempt( hops, options ) };
		return this.attempt.found;

	}

	draw( targetParams = this.input.target ? this.targets[ this.input.target ] : null ) {

		const ctx = this.drawing.clear();
		if ( ! ctx ) return;
		const profile = this.profile;
		drawMouth( ctx, {
			target: profile && targetParams ? profile.curve( targetParams ) : null,
			estimate: this.estimateCurve,
			outlines: this.head?.palate ? [ this.head.palate ] : [],
		}, this.drawing );
		this.drawCount ++;

	}

	/** Size the panel to `width` x `height` CSS pixels: the head and the drawing side by side. */
	resize( width, height ) {

		// The notes wrap within the panel rather than widen it. Each view has a border of 1 px a side.
		this.element.style.width = `${ width }px`;
		const each = Math.floor( ( width - GAP_PX - 4 ) / 2 );
		const viewHeight = Math.max( 160, height - WORDS_PX );
		this.stage.style.width = `${ each }px`;
		this.stage.style.height = `${ viewHeight }px`;
		this.drawing.resize( width - GAP_PX - 4 - each, viewHeight );
		this.head?.frame();
		this.draw();

	}

	/** window.glasshead.listening.mouth: the target, the estimate and what is drawn. */
	debugState() {

		return {
			target: this.input.target,
			estimate: this.estimate && { nearest: this.estimate.nearest, params: this.estimate.params, live: this.estimate.live, frames: this.estimate.frames },
			ghost: this.head?.ghostShown ?? false,
			head: this.head?.status ?? null,
			headFrames: this.head?.frames.drawn ?? 0,
			headPending: this.head?.frames.pending ?? false,
			draws: this.drawCount,
		};

	}

	dispose() {

		this.head?.dispose();
		this.head = null;

	}

}
