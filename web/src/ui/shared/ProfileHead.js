// A still 3D head in profile: the whole head with the sagittal cutaway, framed on the mouth, posed
// at the parameters it is given (the listening page's phoneme target, the clinician's EMA
// recording frame by frame), with another tongue as a ghost when it is given one (the learner's). It draws only when something changes (the viewer draws on demand: a
// pose, a resize); the camera stays still, so the page scrolls over it.
//
// Without WebGL2 there is no 3D view: `status` says 'no-webgl' and `message` why, and the palate
// is still loaded (without a renderer) for the 2D drawing beside it.

import { getAnatomy } from '../../api.js';
import { createArticulation } from '../../scene/Articulation.js';
import { GhostTongue } from '../../scene/GhostTongue.js';
import { Head } from '../../scene/Head.js';
import { viewPose } from '../../scene/viewPresets.js';
import { createHeadStage } from './headStage.js';
import { loadAnatomy } from './loaders.js';
import { MidlineOutline } from './SagittalPanel.js';

/** What the camera frames, mm (project frame): the tongue, the palate and the lips. */
const MOUTH_FOCUS = Object.freeze( { center: [ - 6, - 10, 0 ], radius: 60 } );
/** The part the 2D drawing outlines: the hard palate and the upper teeth (they never move). */
const PALATE_PART = 'maxilla';
/** What the panel says without WebGL2 (the browser's console has the technical reason). */
export const NO_WEBGL_MESSAGE = 'This browser cannot show the 3D head (it needs WebGL2). The drawing beside it still shows the tongues.';

export class ProfileHead {

	/**
	 * @param {HTMLElement} element what the 3D canvas fills (sized by the page)
	 * @param {{ api: object, onChange?: Function, label?: string }} options `onChange()` after
	 *   loading or failing; `label` names the canvas for a screen reader
	 */
	constructor( element, { api, onChange = () => {}, label = 'The head in profile, cut down the middle: the target\'s tongue' } ) {

		this.element = element;
		this.api = api;
		this.onChange = onChange;
		this.status = 'loading';
		this.message = '';
		this.articulation = null;
		this.params = {};
		this.palate = null;
		this.disposed = false;
		const stage = createHeadStage( element, ( message ) => this.fail( 'no-webgl', message ) );
		if ( stage ) {

			( { viewer: this.viewer, head: this.head } = stage );
			// A still profile: no dragging (on a tablet a drag scrolls the page) and no wheel zoom.
			this.viewer.controls.enabled = false;
			this.viewer.renderer.domElement.style.touchAction = 'auto';
			this.viewer.renderer.domElement.setAttribute( 'aria-label', label );
			this.ghostTongue = new GhostTongue();
			this.head.group.add( this.ghostTongue.group );

		} else {

			this.message = NO_WEBGL_MESSAGE;
			this.viewer = null;
			this.head = new Head();

		}

	}

	/**
	 * Load the anatomy and put the articulation in it. `data`: what loadArticulationData gives
	 * (the tongue rig, collision tables, face and velum rigs).
	 */
	async load( data ) {

		try {

			const anatomy = await getAnatomy( this.api );
			// Without a renderer only the palate is needed, for the 2D drawing's outline.
			const meshes = this.viewer ? anatomy.meshes : anatomy.meshes.filter( ( mesh ) => mesh.name === PALATE_PART );
			await loadAnatomy( this.head, meshes, { api: this.api } );
			if ( this.disposed ) return;
			const palate = this.head.part( PALATE_PART );
			if ( palate ) this.palate = new MidlineOutline( null ).update( palate.geometry.attributes.position.array, palate.geometry.index?.array ?? null );
			if ( ! this.viewer ) return this.onChange();
			this.articulation = createArticulation( this.head, this.viewer, data );
			this.head.setTransparency( 0 );
			this.head.setCutaway( true );
			this.frame();
			if ( this.status === 'loading' ) this.status = 'ready';
			this.pose( this.params );

		} catch ( error ) {

			console.warn( `Glasshead: the profile head could not be shown: ${ error.message }` );
			if ( this.viewer ) this.fail( 'failed', `The head could not be loaded: ${ error.message }` );

		}

		this.onChange();

	}

	/** Pose the head at `params` ({ name: value }; {} is the rest posture; unknown names are left out). */
	pose( params ) {

		this.params = params ?? {};
		if ( ! this.articulation ) return;
		const state = this.articulation.state;
		const known = Object.fromEntries( Object.entries( this.params ).filter( ( [ name, value ] ) => state.index.has( name ) && Number.isFinite( value ) ) );
		// A pose that changes nothing draws nothing.
		if ( ! state.assign( known ) ) return;
		this.articulation.update();
		this.viewer.requestRender();

	}

	/**
	 * Show another tongue's mid-sagittal curve as a ghost in the cut head (x y per point, mm; the
	 * learner's, estimated from their voice), or none for null.
	 */
	ghost( curve ) {

		if ( ! this.ghostTongue || ( ! curve && ! this.ghostTongue.visible ) ) return;
		this.ghostTongue.set( curve );
		this.viewer.requestRender();

	}

	/** Whether a ghost tongue shows. */
	get ghostShown() {

		return this.ghostTongue?.visible ?? false;

	}

	/** Frame the mouth in profile for the stage's present shape (after a resize). */
	frame() {

		if ( ! this.viewer || this.status === 'no-webgl' ) return;
		this.viewer.resize();
		this.viewer.flyTo( viewPose( 'profile', MOUTH_FOCUS.center, MOUTH_FOCUS.radius, this.viewer.camera.fov, this.viewer.aspect ), 0 );
		this.viewer.requestRender();

	}

	/** Frames the head has drawn, and whether a change waits to be drawn (for the page's debug state). */
	get frames() {

		return { drawn: this.viewer?.frameCount ?? 0, pending: this.viewer?.renderPending ?? false };

	}

	fail( status, message ) {

		this.status = status;
		this.message = message;
		if ( status === 'no-webgl' && this.viewer ) this.onChange(); // the context was lost after loading

	}

	dispose() {

		this.disposed = true;
		this.ghostTongue?.dispose();
		this.articulation?.dispose();
		this.viewer?.dispose();
		this.head?.dispose();
		this.viewer = null;

	}

}
