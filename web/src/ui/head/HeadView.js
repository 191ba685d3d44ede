// The head view (route `#/`): the 3D head with its control panel.

import { getAnatomy } from '../../api.js';
import { Vector3 } from 'three';
import { VIEW_NAMES, viewPose } from '../../scene/viewPresets.js';
import { Controls } from './Controls.js';
import { h } from '../shared/dom.js';
import { createFirstRunHint } from './FirstRunHint.js';
import './headTools.css';
import { LabelLayer } from '../shared/LabelLayer.js';
import { EyeMotion } from '../../scene/Eyes.js';
import { loadAnatomy, loadArticulation, loadLandmarks } from '../shared/loaders.js';
import { View } from '../shared/View.js';

export const DEFAULT_STATE = Object.freeze( { transparency: 0, cutaway: false, labels: false, view: 'three-quarter' } );

/** Duration of a camera move between views. */
const FLIGHT_MS = 650;

export class HeadView extends View {

	/** @param {{ api?: object }} options the HTTP client everything is loaded through */
	constructor( options ) {

		super( options );
		this.state = { ...DEFAULT_STATE, loaded: false, error: null, meshes: [] };

	}

	/** Build the view inside `container` and start loading. */
	mount( container ) {

		this.stage = h( 'div', { className: 'stage' } );
		this.attach( container, h( 'div', { className: 'head-view' }, this.stage ) );

		this.controls = new Controls( {
			onTransparency: ( percent ) => this.setTransparency( percent ),
			onCutaway: ( on ) => this.setCutaway( on ),
			onLabels: ( on ) => this.setLabels( on ),
			onView: ( name ) => this.setView( name ),
		}, this.state );
		this.root.append( this.controls.element );
		this.controls.setEnabled( false );

		this.registerDebugFields();

		if ( ! this.mountStage( this.stage ) ) return this;
		const hint = createFirstRunHint();
		if ( hint ) this.stage.append( hint );
		this.load();
		return this;

	}

	registerDebugFields() {

		this.debugFields( {
			loaded: () => this.state.loaded,
			error: () => this.state.error,
			meshes: () => this.state.meshes,
			transparency: () => this.state.transparency,
			cutaway: () => this.state.cutaway,
			view: () => this.state.view,
			webgl2: () => ( this.viewer ? this.viewer.webgl2 : false ),
			...this.stageDebugFields(),
			mouthRect: () => ( this.viewer && this.state.loaded ? this.viewer.screenRect( this.head.mouthBox() ) : null ),
			headRect: () => ( this.viewer && this.state.loaded ? this.viewer.screenRectOfPoints( this.head.skinPoints() ) : null ),
			eyes: () => this.eyes?.state() ?? null,
			airProbe: () => ( this.viewer && this.state.loaded && this.head.air ? this.head.air.probe( this.viewer ) : null ),
			cranialProbe: () => ( this.viewer && this.state.loaded && this.head.cranial ? this.head.cranial.probe( this.viewer ) : null ),
		} );

	}

	async load() {

		this.controls.showStatus( 'Loading the anatomy…' );
		this.controls.showProgress( 0, 0 );
		try {

			const anatomy = await getAnatomy( this.api );
			this.controls.showStatus( `Loading meshes: 0 of ${ anatomy.meshes.length }` );
			await loadAnatomy( this.head, anatomy.meshes, {
				api: this.api,
				onProgress: ( loaded, total ) => {

					this.controls.showStatus( `Loading meshes: ${ loaded } of ${ total }` );
					this.controls.showProgress( loaded, total );

				},
			} );

		} catch ( error ) {

			this.fail( error.message );
			return;

		}

		if ( ! this.viewer ) return; // unmounted while loading
		this.state.meshes = this.head.meshInfo();
		this.articulation = await loadArticulation( this.head, this.viewer, { api: this.api, tables: 'whenMoved' } ).catch( ( error ) => console.warn( `Glasshead: showing the rest tongue; the tongue rig did not load: ${ error.message }` ) );
		if ( ! this.viewer ) return this.articulation?.dispose(); // unmounted while loading
		await ( await import( '../shared/HeadEpg.js' ) ).attachHeadEpg( this, { api: this.api } ); // electrodes on the palate, live palatogram
		await this.attachLabels();
		await this.attachTargets();
		if ( ! this.viewer ) return; // unmounted while loading: someone went to another view
		// `?still` in the page's address: no blinks (tests that a still head draws nothing use it).
		this.eyes = new EyeMotion( this.head, this.viewer, { blink: ! new URLSearchParams( location.search ).has( 'still' ) } );
		this.head.setTransparency( this.state.transparency );
		this.head.setCutaway( this.state.cutaway );
		this.fitViews();
		this.viewer.flyTo( this.poses[ this.state.view ], 0 );
		this.viewer.requestRender();
		this.state.loaded = true;
		this.controls.setEnabled( true );
		this.controls.showStatus( '' );
		this.controls.showProgress( null );

	}

	/** Camera poses of the named views, framing the whole head. */
	fitViews() {

		// The head's largest extent, not its bounding sphere (which would leave the head small in
		// every view): the camera turns about the vertical, and the head is taller than it is deep.
		const box = this.head.boundingBox();
		const size = box.getSize( new Vector3() );
		const radius = 0.52 * Math.max( size.x, size.y, size.z );
		const center = box.getCenter( new Vector3() ).toArray();
		this.poses = {};
		for ( const name of VIEW_NAMES ) this.poses[ name ] = viewPose( name, center, radius, this.viewer.camera.fov, this.viewer.aspect );

	}

	setTransparency( percent ) {

		this.state.transparency = percent;
		this.head.setTransparency( percent );
		this.viewer.requestRender();

	}

	setCutaway( on ) {

		this.state.cutaway = on;
		this.controls.setCutaway( on );
		this.head.setCutaway( on );
		this.viewer.requestRender();

	}

	/** The label layer, from GET /anatomy/landmarks; without them the view works unlabelled. */
	async attachLabels() {

		try {

			const document = await loadLandmarks( { api: this.api } );
			if ( ! this.viewer ) return;
			this.labels = new LabelLayer( { document, head: this.head, viewer: this.viewer, stage: this.stage, obstacles: () => [ this.controls.element, ...this.stage.querySelectorAll( '.first-run-hint' ) ] } );
			this.labels.setVisible( this.state.labels );

		} catch ( error ) {

			console.warn( `Glasshead: no labels; the landmarks did not load: ${ error.message }` );

		}

	}

	/** The chooser of saved poses and phoneme targets, when the tongue rig loaded. */
	async attachTargets() {

		if ( ! this.articulation ) return;
		const { HeadTargets } = await import( './HeadTargets.js' );
		if ( ! this.viewer ) return;
		this.targets = new HeadTargets( { articulation: this.articulation, api: this.api, onChange: () => this.viewer?.requestRender() } );
		this.controls.element.append( this.targets.element );
		this.onUnmount( () => this.targets.dispose() );
		this.targets.load(); // the lists fill in while the view is already in use

	}

	setLabels( on ) {

		this.state.labels = on;
		this.controls.setLabels( on );
		this.labels?.setVisible( on );
		this.viewer.requestRender();

	}

	setView( name ) {

		this.state.view = name;
		this.controls.setView( name );
		if ( this.poses ) this.viewer.flyTo( this.poses[ name ], FLIGHT_MS );

	}

	fail( message ) {

		this.state.error = message;
		this.controls.showStatus( '' );
		this.controls.showProgress( null );
		this.controls.showError( message );
		console.error( `Glasshead: ${ message }` );

	}

	dispose() {

		this.articulation?.dispose();
		this.labels?.dispose();
		this.eyes?.dispose();

	}

}

/** Route entry for the view registry. */
export function mountHeadView( container ) {

	return new HeadView().mount( container );

}
