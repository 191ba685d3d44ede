// The target on the 3D palate, for the clinician view: the palate, the target's tongue (collision
// corrected, as the browser computes it every frame) seen through, and the electrodes, dots and
// contacted squares (Cohen, Beskow and Massaro 1998, Figures 7 and 8). The camera looks up at the
// palate from below and in front, where a clinician pictures an EPG plate.

import { api as pageApi, getAnatomy } from '../../api.js';
import { Electrodes } from '../../scene/Electrodes.js';
import { createEpgLive } from '../../scene/EpgLive.js';
import { Head } from '../../scene/Head.js';
import { Articulation, parameterDefinitions, TONGUE_PART } from '../../scene/Articulation.js';
import { Viewer } from '../../scene/Viewer.js';
import { ParamState } from '../../core/paramState.js';
import { TongueRig } from '../../core/tongue.js';
import { loadAnatomy, loadCollisionTables } from '../shared/loaders.js';

/** Meshes this view needs: the palate and the tongue (the jaw would hide the palate). */
const PARTS = Object.freeze( [ 'maxilla', TONGUE_PART ] );
/** Opacity of the tongue, so the electrodes it touches show through it. */
const TONGUE_OPACITY = 0.28;
/**
 * Camera: below the palate looking up at it, the front at the top of the picture and the subject's
 * left on the left, as the flat palatogram beside it (mm; `up` is the camera's up vector).
 */
const CAMERA = Object.freeze( { target: [ - 3, 17, 0 ], position: [ - 30, - 96, 0 ], up: [ 1, 0, 0 ] } );

export class TargetPalate3D {

	/**
	 * container: the element the canvas fills. Throws when WebGL2 is missing.
	 * @param {{ api?: object }} options the HTTP client everything is loaded through
	 */
	constructor( container, { api = pageApi } = {} ) {

		this.api = api;
		this.viewer = new Viewer( container, { fov: 32 } );
		this.viewer.controls.minDistance = 30;
		this.head = new Head();
		this.viewer.scene.add( this.head.group );
		this.articulation = null;
		this.live = null;
		this.electrodes = null;
		this.ready = this.load();

	}

	async load() {

		const [ anatomy, layout, definition, tables ] = await Promise.all( [
			getAnatomy( this.api ),
			this.api.get( 'epg/layout?grid=reading62' ),
			this.api.get( 'tongue/rig' ),
			loadCollisionTables( { api: this.api } ),
		] );
		const meshes = anatomy.meshes.filter( ( m ) => PARTS.includes( m.name ) );
		await loadAnatomy( this.head, meshes, { api: this.api } );
		if ( ! this.viewer ) return this;
		const rig = new TongueRig( definition );
		this.state = new ParamState( parameterDefinitions( definition ) );
		this.articulation = new Articulation( rig, this.state, { tables } ).attach( this.head );
		const tongue = this.head.part( TONGUE_PART );
		for ( const mesh of tongue?.meshes ?? [] ) {

			mesh.material.transparent = true;
			mesh.material.opacity = TONGUE_OPACITY;
			mesh.material.depthWrite = false;
			mesh.material.needsUpdate = true;

		}

		this.live = createEpgLive( { layout: { grids: { reading62: layout } }, tongueTriangles: rig.index, vertexCount: rig.vertexCount } );
		this.electrodes = new Electrodes( layout, { clippingPlanes: [ this.head.clipPlane ] } );
		this.head.group.add( this.electrodes.group );
		this.live.onUpdate( ( live ) => {

			this.electrodes.show( live.frame );
			this.viewer?.requestRender();

		} );
		this.articulation.onCorrected( ( positions ) => this.live.update( positions ) );
		this.articulation.attachViewer( this.viewer );
		this.live.update( this.articulation.positions );
		this.viewer.camera.up.fromArray( CAMERA.up );
		this.viewer.applyPose( CAMERA );
		this.viewer.requestRender();
		return this;

	}

	/** Show the tongue of a parameter set ({ name: value }; names left out are neutral). */
	async showParams( params ) {

		await this.ready;
		if ( ! this.state ) return null;
		// The palate view poses the tongue and jaw only: a target's lip and velum values (phoneme
		// targets set every rig's parameters) do not touch the palate.
		const known = new Set( this.state.names );
		this.state.assign( Object.fromEntries( Object.entries( params ?? {} ).filter( ( [ name ] ) => known.has( name ) ) ) );
		this.articulation.update();
		return this.live.report();

	}

	dispose() {

		this.articulation?.dispose();
		this.electrodes?.dispose();
		this.viewer?.dispose();
		this.head?.dispose();
		this.viewer = null;

	}

}
