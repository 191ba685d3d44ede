// A lesson item on the speech player's head (ui/speak/SpeechView.js): its views (skin transparency,
// cutaway, the 2D diagram, cues, labels, the EPG card), its target said through POST /utterances
// with its audio, its speed, and for a static presentation the target held. Shared by the teacher's
// lesson runner and the child's practice, which both mount a SpeechView with `sayOnLoad: false`
// and hand it here; SpeechView stays the one player.
//
//   const view = new SpeechView( { sayOnLoad: false } ).mount( element );
//   const presenter = new ItemPresenter( view );
//   await presenter.present( item );   // views, target, speed, hold
//   presenter.replay();                 // from the start, with its sound

import { api } from '../../api.js';
import { zoomedPose } from '../../scene/viewPresets.js';
import { itemRequest, itemSettings, phonemeIndex } from './LessonRunnerItems.js';

/** How long the camera takes to move to an item's view, ms. */
const CAMERA_FLIGHT_MS = 500;
/** The phoneme inventory (GET /phonemes) as itemRequest reads it, fetched once per page. */
let inventory = null;

/** The inventory, or an empty one when it cannot be read (a phoneme is then said as it comes). */
export function phonemeInventory( client = api ) {

	inventory ??= client.get( 'phonemes' ).then( ( body ) => phonemeIndex( body.phonemes ), () => {

		inventory = null; // asked again next time
		return new Map();

	} );
	return inventory;

}

/** The first phone that is not silence, or -1. */
export function firstSpokenPhone( phones ) {

	return phones.findIndex( ( phone ) => phone.symbol !== 'sil' );

}

export class ItemPresenter {

	/**
	 * @param {object} view a mounted SpeechView
	 * @param {{ obstacles?: () => Array<Element|null>, inventory?: () => Promise<Map> }} options
	 *   what lies over the head that the labels keep off (the target in big letters), and the
	 *   phoneme inventory's reader (GET /phonemes, once per page)
	 */
	constructor( view, { obstacles = () => [], inventory = () => phonemeInventory() } = {} ) {

		this.view = view;
		this.obstacles = obstacles;
		this.inventory = inventory;
		this.settings = null;
		this.item = null;
		this.presenting = 0;
		this.wasPlaying = false;
		this.labels = null;
		/** How many times the target was played again after it was first said. */
		this.plays = 0;

	}

	/** Show `item`: its views, its target said (ready to play) and, static, its target held. */
	async present( item ) {

		const view = this.view;
		const presenting = ++ this.presenting;
		if ( ! await view.ready || ! view.viewer ) return false;
		this.item = item;
		this.settings = itemSettings( item );
		this.plays = 0;
		const [ phonemes ] = await Promise.all( [ this.inventory(), this.applyViews( this.settings ) ] );
		if ( presenting !== this.presenting ) return false;
		await view.say( itemRequest( item, phonemes ) );
		if ( presenting !== this.presenting || ! view.viewer || ! view.utterance || view.busy ) return false;
		view.setSpeed( this.settings.speed );
		if ( this.settings.hold ) await this.hold();
		this.watch();
		return presenting === this.presenting;

	}

	/**
	 * The item's views on the head and beside it: the camera's view and zoom, the skin, the
	 * panels, and the labels it names (the label layer loaded when first wanted).
	 */
	async applyViews( settings ) {

		const view = this.view;
		const camera = view.viewer.camera;
		view.viewer.flyTo( zoomedPose( settings.camera, settings.zoom, camera.fov, view.viewer.aspect ), this.cameraSet ? CAMERA_FLIGHT_MS : 0 );
		this.cameraSet = true;
		view.state.skin = settings.transparency > 0;
		if ( settings.transparency > 0 ) view.state.transparency = settings.transparency;
		view.state.cutaway = settings.cutaway;
		view.apply();
		const diagram = view.panels?.diagramCanvas.element.closest( 'section' );
		if ( diagram ) {

			diagram.classList.add( 'sp-diagram-section' );
			diagram.hidden = ! settings.diagram;

		}

		view.root.classList.toggle( 'with-diagram', settings.diagram );
		const cues = view.panels?.cues;
		if ( cues?.layer ) {

			cues.layer.set( { visible: settings.cues } );
			cues.sync();

		}

		if ( view.epg ) {

			view.epg.panel.hidden = ! settings.epg;
			view.epg.electrodes.group.visible = settings.epg;

		}

		if ( settings.labels && ! this.labels && view.landmarks ) {

			const { LabelLayer } = await import( '../shared/LabelLayer.js' );
			if ( ! view.viewer || this.labels ) return;
			this.labels = new LabelLayer( { document: view.landmarks, head: view.head, viewer: view.viewer, stage: view.stage, obstacles: this.obstacles } );
			view.unregister.push( () => this.labels.dispose() );

		}

		this.labels?.setVisible( settings.labels );
		view.viewer.requestRender();

	}

	/**
	 * The labels the item names that the camera cannot see at its settings (bone in the way),
	 * once the camera has reached the item's view; [] when it names none.
	 */
	async hiddenLabels() {

		const viewer = this.view.viewer;
		if ( viewer?.animating ) await new Promise( ( resolve ) => {

			const stop = viewer.onFrame( () => {

				if ( viewer.animating ) return false;
				stop();
				resolve();
				return false;

			} );

		} );
		return this.labels && this.view.viewer ? this.labels.hiddenLabels() : [];

	}

	/** Hold the target of the first spoken phone (static presentation). */
	async hold() {

		const view = this.view;
		const index = firstSpokenPhone( view.utterance.phones );
		if ( index < 0 ) return;
		view.goToPhone( index );
		await view.holdCurrent();

	}

	/** Play, or pause where it is. */
	togglePlay() {

		if ( ! this.view.utterance ) return;
		if ( ! this.view.clock.playing ) this.plays += 1;
		this.view.togglePlay();

	}

	/** Say the target again from its start, with its sound. */
	replay() {

		const view = this.view;
		if ( ! view.utterance ) return;
		view.state.hold = null;
		view.clock.pause();
		view.seek( 0 );
		this.togglePlay();

	}

	/** Slow motion on (SLOW_SPEED) or back at the item's own speed. */
	setSpeed( speed ) {

		this.view.setSpeed( speed );

	}

	/** A static item is held again when it has been played to its end. */
	watch() {

		if ( this.unwatch ) return;
		const view = this.view;
		this.unwatch = view.viewer.onFrame( () => {

			const playing = view.clock.playing;
			const ended = this.wasPlaying && ! playing && view.clock.time >= view.clock.duration;
			this.wasPlaying = playing;
			if ( ended && this.settings?.hold ) this.hold();
			return false;

		} );
		view.unregister.push( this.unwatch );

	}

}
