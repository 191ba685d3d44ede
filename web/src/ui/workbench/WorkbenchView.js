// The workbench (route `#/workbench`), the development system of the paper's Figure 4: sliders
// for every parameter in groups, the tongue in 3D over the palate and jaw, the mid-sagittal curve
// with its lettered control points, the three coronal sections with the blending functions, the
// collision liner and voxel table as toggles, reset, copy and paste of the parameters as JSON,
// and saving them as a named pose.

import { Box3, BufferAttribute, BufferGeometry, Points, PointsMaterial } from 'three';
import { getAnatomy } from '../../api.js';
import { FLAG_CORRECTED } from '../../core/constants.js';
import { LinerWireframe } from '../../scene/LinerWireframe.js';
import { VoxelDots } from '../../scene/VoxelDots.js';
import { fitDistance, VIEW_NAMES, viewPose } from '../../scene/viewPresets.js';
import { h } from '../shared/dom.js';
import { HiDpiCanvas } from '../shared/hidpiCanvas.js';
import { ParameterPanel } from './ParameterPanel.js';
import { PoseBox } from './PoseBox.js';
import { drawSagittalPanel, MidlineOutline, PANEL_COLORS, sagittalCurve } from '../shared/SagittalPanel.js';
import { blendingFunctions, coronalSection, drawSectionsPanel, sectionControls, sectionStations } from './SectionsPanel.js';
import './workbench.css';
import './observation.css';
import '../shared/signin.css';
import { loadAnatomy, loadArticulation, loadLandmarks } from '../shared/loaders.js';
import { View } from '../shared/View.js';
import { DiagramSection } from '../../scene/DiagramSection.js';
import { drawDiagram } from '../shared/DiagramPanel.js';
import { WorkbenchCues } from '../shared/WorkbenchCues.js';
import { mountObservationPanels } from './ObservationOverlay.js';
import { FormantPanel } from './FormantPanel.js';

/** The part of the head the 3D view frames: the oral cavity, tongue and jaw (mm). */
const FOCUS = Object.freeze( { center: [ - 8, - 4, 0 ], radius: 46 } );
/** The head view's views, and one from above the front of the mouth onto the tongue's back. */
const VIEWS = Object.freeze( [ ...VIEW_NAMES, 'above' ] );
const VIEW_LABELS = Object.freeze( { front: 'Front', profile: 'Profile', 'three-quarter': 'Three-quarter', above: 'Above' } );
/** Direction from the target to the camera of the view from above: up, forward and to the cut side. */
const ABOVE_DIRECTION = Object.freeze( [ 0.55, 0.78, - 0.3 ] );
/** Meshes the workbench never shows (the skull above the palate hides the mouth from above). */
const HIDDEN_PARTS = Object.freeze( [ 'cranium' ] );
/** Meshes of the toggles that uncover the tongue: the jaw and lips around it, the palate over it. */
const TOGGLED_PARTS = Object.freeze( { jaw: [ 'mandible', 'upper_lip', 'lower_lip' ], palate: [ 'maxilla' ], tongue: [ 'tongue_rest' ] } );
const PANEL_SIZE = Object.freeze( { sagittal: [ 380, 290 ], sections: [ 380, 330 ], diagram: [ 380, 356 ] } );
const CONTACT_COLOR = '#3d0710';

export const WORKBENCH_DEFAULTS = Object.freeze( { skin: false, jaw: true, palate: true, tongue: true, cutaway: true, liner: false, voxels: false, contacts: true, view: 'three-quarter' } );

export class WorkbenchView extends View {

	/** @param {{ api?: object }} options the HTTP client everything is loaded and saved through */
	constructor( options ) {

		super( options );
		this.state = { ...WORKBENCH_DEFAULTS, loaded: false, error: null };

	}

	mount( container ) {

		this.stage = h( 'div', { className: 'stage wb-stage' } );
		this.status = h( 'p', { className: 'status', role: 'status', 'aria-live': 'polite' }, 'Loading the anatomy…' );
		this.error = h( 'p', { className: 'error', role: 'alert', hidden: '' } );
		this.side = h( 'aside', { className: 'wb-side', 'aria-label': 'Workbench panels' }, this.status, this.error );
		this.left = h( 'div', { className: 'wb-left' }, h( 'h1', { className: 'wb-title' }, 'Workbench' ) );
		this.attach( container, h( 'div', { className: 'workbench' }, this.left, this.stage, this.side ) );
		this.registerDebugFields();

		if ( ! this.mountStage( this.stage ) ) return this;
		this.load();
		return this;

	}

	registerDebugFields() {

		this.debugFields( {
			loaded: () => this.state.loaded,
			error: () => this.state.error,
			view: () => this.state.view,
			workbench: () => ( {
				skin: this.state.skin, jaw: this.state.jaw, palate: this.state.palate, tongue: this.state.tongue, cutaway: this.state.cutaway, liner: this.state.liner, voxels: this.state.voxels,
				contacts: this.state.contacts, pasteError: this.poseBox?.pasteError ?? null, poseStatus: this.poseBox?.poseStatus ?? null, poseSaving: this.poseBox?.saving ?? null,
				linerSegments: this.liner?.segmentCount ?? 0, voxelCounts: this.voxels?.counts ?? null,
				tablesError: this.articulation?.tablesError ?? null, panelDraws: this.panelDraws ?? 0,
				diagramDraws: this.diagramDraws ?? 0, landmarksError: this.landmarksError ?? null,
			} ),
			...this.stageDebugFields(),
			tongueRect: () => ( this.state.loaded ? this.viewer.screenRect( new Box3().setFromBufferAttribute( this.articulation.geometry.attributes.position ) ) : null ),
		} );

	}

	async load() {

		try {

			const anatomy = await getAnatomy( this.api );
			await loadAnatomy( this.head, anatomy.meshes, {
				api: this.api,
				onProgress: ( loaded, total ) => this.showStatus( `Loading meshes: ${ loaded } of ${ total }` ),
			} );
			if ( ! this.viewer ) return;
			this.showStatus( 'Loading the tongue rig and the collision tables…' );
			this.articulation = await loadArticulation( this.head, this.viewer, { api: this.api } );
			// The diagram names the constriction's place from the landmarks; it is drawn without them.
			this.landmarks = await loadLandmarks( { api: this.api } ).catch( ( error ) => {

				this.landmarksError = error.message;
				return null;

			} );

		} catch ( error ) {

			this.fail( error.message );
			return;

		}

		if ( ! this.viewer ) return this.articulation.dispose(); // unmounted while loading
		const articulation = this.articulation;
		this.onUnmount( () => articulation.dispose() );
		this.buildScene();
		this.buildPanels();
		this.apply();
		this.setView( this.state.view, 0 );
		this.state.loaded = true;
		this.showStatus( articulation.tablesError ? `No collision correction: ${ articulation.tablesError }` : '' );

	}

	/** The collision figures and the contact dots, added to the 3D scene. */
	buildScene() {

		const { tables } = this.articulation;
		if ( tables ) {

			this.liner = new LinerWireframe( tables );
			this.voxels = new VoxelDots( tables );
			this.liner.material.clippingPlanes = [ this.head.clipPlane ];
			for ( const points of this.voxels.children ) points.material.clippingPlanes = [ this.head.clipPlane ];
			this.viewer.scene.add( this.liner, this.voxels );

		}

		const count = this.articulation.vertexCount;
		const geometry = new BufferGeometry();
		geometry.setAttribute( 'position', new BufferAttribute( new Float32Array( 3 * count ), 3 ) );
		geometry.setDrawRange( 0, 0 );
		// Drawn over everything: the contacts lie on the palate, which would hide them half the time.
		this.contacts = new Points( geometry, new PointsMaterial( { color: CONTACT_COLOR, size: 3, sizeAttenuation: false, depthTest: false, clippingPlanes: [ this.head.clipPlane ] } ) );
		this.contacts.name = 'collision-contacts';
		this.contacts.frustumCulled = false;
		this.contacts.renderOrder = 8;
		this.viewer.scene.add( this.contacts );
		this.onUnmount( this.articulation.onCorrected( ( positions, articulation ) => this.showContacts( positions, articulation.flags ) ) );
		this.showContacts( this.articulation.positions, this.articulation.flags );

	}

	/** The corrected vertices (on the palate or teeth) as dark dots: where the tongue touches. */
	showContacts( positions, flags ) {

		const attribute = this.contacts.geometry.attributes.position;
		const target = attribute.array;
		let n = 0;
		for ( let v = 0; v < flags.length; v ++ ) {

			if ( flags[ v ] !== FLAG_CORRECTED ) continue;
			target[ 3 * n ] = positions[ 3 * v ];
			target[ 3 * n + 1 ] = positions[ 3 * v + 1 ];
			target[ 3 * n + 2 ] = positions[ 3 * v + 2 ];
			n ++;

		}

		attribute.needsUpdate = true;
		this.contacts.geometry.setDrawRange( 0, n );

	}

	buildPanels() {

		const articulation = this.articulation;
		const { state, rig } = articulation;
		this.parameters = new ParameterPanel( state );
		// Changes are drawn in the next frame (whose hook recomputes); until then a render is pending.
		this.onUnmount( state.onChange( () => this.viewer.requestRender() ) );
		this.left.append( this.parameters.element );
		this.poseBox = new PoseBox( state, { api: this.api } );
		this.onUnmount( () => this.poseBox.dispose() );

		const canvas = ( [ width, height ], ariaLabel ) => new HiDpiCanvas( { width, height, ariaLabel, className: 'wb-canvas' } );

		this.sagittalCanvas = canvas( PANEL_SIZE.sagittal, 'Mid-sagittal section: the tongue curve with its lettered control points' );
		this.sectionsCanvas = canvas( PANEL_SIZE.sections, 'The front, middle and back coronal sections and the blending functions' );
		this.diagramCanvas = canvas( PANEL_SIZE.diagram, 'Diagram: the vocal tract cut at the mid-sagittal plane, with the narrowest constriction marked' );
		this.diagramCanvas.element.classList.add( 'wb-diagram' );
		this.diagram = new DiagramSection( this.head, { landmarks: this.landmarks } );
		this.onUnmount( this.diagram.registerDebugField() );
		this.diagramParts = Object.fromEntries( [ 'pharynx', 'larynx', 'palate', 'mandible', 'velum', 'upperLip', 'lowerLip', 'tongue' ].map( ( key ) => [ key, this.diagram.parts( key ) ] ) );

		this.toggles = new Map( [ [ 'skin', 'Skin' ], [ 'jaw', 'Jaw & lips' ], [ 'palate', 'Palate' ], [ 'tongue', 'Tongue' ], [ 'cutaway', 'Cutaway' ], [ 'contacts', 'Contacts' ], [ 'liner', 'Liner' ], [ 'voxels', 'Voxels' ] ].map( ( [ key, label ] ) => [ key, h( 'button', {
			type: 'button', className: 'toggle wb-toggle', 'aria-pressed': String( this.state[ key ] ),
			onClick: () => this.toggle( key ),
		}, label ) ] ) );
		this.viewButtons = new Map( VIEWS.map( ( name ) => [ name, h( 'button', {
			type: 'button', className: 'wb-toggle', 'aria-pressed': String( name === this.state.view ), onClick: () => this.setView( name ),
		}, VIEW_LABELS[ name ] ) ] ) );
		// The head's own formants, from the diagram's section; loaded beside the panels.
		this.formants = new FormantPanel( { api: this.api, diagram: this.diagram, state, velumRig: articulation.velum?.rig ?? null } );
		this.onUnmount( () => this.formants.dispose() );
		this.formants.load();
		this.side.append(
			h( 'div', { className: 'wb-buttons', role: 'group', 'aria-label': 'Show' }, ...this.toggles.values() ),
			h( 'div', { className: 'wb-buttons', role: 'group', 'aria-label': 'View' }, ...this.viewButtons.values() ),
			this.sagittalCanvas.element,
			this.sectionsCanvas.element,
			this.diagramCanvas.element,
			this.formants.element,
			this.poseBox.element,
		);

		// The anatomy cut at z = 0: the palate once, the jaw and lips again with every frame (the
		// jaw moves; a face rig deforms the lips).
		this.outlines = [
			[ 'maxilla', PANEL_COLORS.palate ], [ 'mandible', PANEL_COLORS.jaw ],
			[ 'upper_lip', PANEL_COLORS.lip ], [ 'lower_lip', PANEL_COLORS.lip ],
		].filter( ( [ name ] ) => this.head.part( name ) ).map( ( [ name, color ] ) => Object.assign( new MidlineOutline( color ), { part: this.head.part( name ) } ) );
		this.updateOutlines( true );

		const surface = rig.createSurface();
		rig.evaluate( state.neutral, surface );
		this.restCurve = sagittalCurve( rig, surface.positions, new Float64Array( 2 * rig.stationCount ) );
		this.curve = new Float64Array( 2 * rig.stationCount );
		this.rawCurve = new Float64Array( 2 * rig.stationCount );
		this.letters = rig.definition.sagittal.control_points.map( ( p ) => p.name );
		this.stations = sectionStations( rig );
		this.blends = blendingFunctions( rig );
		const ringLength = 2 * ( rig.pageCount + 2 );
		this.sections = this.stations.map( ( station ) => ( {
			rest: coronalSection( rig, surface.positions, station, rig.hub, rig.direction, new Float64Array( ringLength ) ),
			points: new Float64Array( ringLength ),
			controls: new Float64Array( 2 * rig.controlCount ),
		} ) );
		this.panelDraws = 0;
		this.onUnmount( articulation.onCorrected( () => this.drawPanels() ) );
		this.drawPanels();
		// After the panels' hook, so that the cues read this frame's constriction. The voice and
		// the air are the chosen phoneme target's while the sliders show it (voiced or not, its
		// glottis, its closure or channel); a voiced sound with no phoneme otherwise.
		const sound = () => this.phonemeChooser?.control.shownFeatures() ?? null;
		this.cues = new WorkbenchCues( {
			viewer: this.viewer, articulation, diagram: this.diagram, landmarks: this.landmarks,
			sound, voiced: () => sound()?.voiced ?? true,
		} );
		this.onUnmount( () => this.cues.dispose() );
		this.side.querySelector( '[aria-label="View"]' ).after( this.cues.element );
		this.onUnmount( mountObservationPanels( this ) ); // its hook after the panels': it draws over them

	}

	/** Recut the parts that move (all of them when `all`). */
	updateOutlines( all = false ) {

		for ( const outline of this.outlines ) {

			const { part } = outline;
			if ( ! all && part.name === 'maxilla' ) continue;
			outline.update( part.geometry.attributes.position.array, part.geometry.index?.array ?? null, part.group.matrixAutoUpdate ? null : part.group.matrix.elements );

		}

	}

	/** Redraw the 2D panels from the articulation's last frame. */
	drawPanels() {

		this.updateOutlines();
		const a = this.articulation;
		const rig = a.rig;
		sagittalCurve( rig, a.positions, this.curve );
		sagittalCurve( rig, a.surface.positions, this.rawCurve );
		drawSagittalPanel( this.sagittalCanvas.ctx, {
			curve: this.curve, restCurve: this.restCurve, rawCurve: a.stats[ 2 ] > 0 ? this.rawCurve : null, points: a.sagittalPoints, letters: this.letters,
			hub: a.hub, origin: a.tables ? a.tables.origin : null, outlines: this.outlines,
		}, this.sagittalCanvas );
		this.sections.forEach( ( section, s ) => {

			coronalSection( rig, a.positions, this.stations[ s ], a.hub, a.directions, section.points );
			sectionControls( rig, a.controls, a.stationStretch, this.stations[ s ], section.controls );

		} );
		drawSectionsPanel( this.sectionsCanvas.ctx, { sections: this.sections, stations: this.stations, blends: this.blends }, this.sectionsCanvas );
		this.panelDraws ++;
		this.diagram.update();
		drawDiagram( this.diagramCanvas.ctx, { parts: this.diagramParts, air: this.diagram.polygon, constriction: this.diagram.constriction() }, this.diagramCanvas );
		this.diagramDraws = ( this.diagramDraws ?? 0 ) + 1;
		this.formants?.update();

	}

	toggle( key ) {

		this.state[ key ] = ! this.state[ key ];
		this.apply();

	}

	/** Show the toggles' state in the scene and on the buttons. */
	apply() {

		this.head.setTransparency( this.state.skin ? 0 : 100 );
		this.head.setCutaway( this.state.cutaway );
		for ( const name of HIDDEN_PARTS ) setPartVisible( this.head, name, false );
		for ( const [ key, names ] of Object.entries( TOGGLED_PARTS ) ) for ( const name of names ) setPartVisible( this.head, name, this.state[ key ] );
		if ( this.liner ) this.liner.visible = this.state.liner;
		if ( this.voxels ) this.voxels.visible = this.state.voxels;
		this.contacts.visible = this.state.contacts;
		for ( const [ key, button ] of this.toggles ) {

			button.setAttribute( 'aria-pressed', String( this.state[ key ] ) );
			if ( ( key === 'liner' || key === 'voxels' ) && ! this.articulation.tables ) button.disabled = true;

		}

		this.viewer.requestRender();

	}

	setView( name, durationMs = 600 ) {

		this.state.view = name;
		for ( const [ view, button ] of this.viewButtons ?? [] ) button.setAttribute( 'aria-pressed', String( view === name ) );
		this.viewer.flyTo( workbenchPose( name, this.viewer.camera.fov, this.viewer.aspect ), durationMs );
		this.viewer.requestRender();

	}

	showStatus( text ) {

		this.status.textContent = text;

	}

	fail( message ) {

		this.state.error = message;
		this.showStatus( '' );
		this.error.textContent = message;
		this.error.hidden = false;
		console.error( `Glasshead: ${ message }` );

	}

	dispose() {

		this.parameters?.dispose();
		this.liner?.dispose();
		this.voxels?.dispose();
		this.contacts?.geometry.dispose();
		this.contacts?.material.dispose();

	}

}

function setPartVisible( head, name, visible ) {

	const part = head.part( name );
	if ( part ) part.group.visible = visible;

}

/** Camera pose { position, target } of a workbench view around the mouth. */
export function workbenchPose( name, fovDeg, aspect ) {

	if ( name !== 'above' ) return viewPose( name, FOCUS.center, FOCUS.radius, fovDeg, aspect );
	const distance = fitDistance( FOCUS.radius, fovDeg, aspect );
	const norm = Math.hypot( ...ABOVE_DIRECTION );
	return {
		position: FOCUS.center.map( ( c, k ) => c + ABOVE_DIRECTION[ k ] / norm * distance ),
		target: [ ...FOCUS.center ],
	};

}

/** Route entry for the view registry. */
export function mountWorkbenchView( container ) {

	return new WorkbenchView().mount( container );

}
