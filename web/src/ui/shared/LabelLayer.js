// The label layer: names the parts of the mouth and throat and the places of articulation at
// their landmarks (GET /anatomy/landmarks, handed in: the layer fetches nothing), as an HTML
// overlay over the 3D view with a dot and a leader line per label; and names the part under the
// pointer (hover, or a tap on a touch screen) by a raycast against the head's meshes. Labels keep
// off the panels over or beside the view: the stage's other children (the EPG card) and the
// elements `obstacles()` gives (the side panel).
//
// window.glasshead.labels = { visible, count, names, hidden, hovered, overlapping }: `hidden` names
// the labels on show whose point the camera cannot see (bone in the way).

import { Raycaster, Vector2, Vector3 } from 'three';
import { registerDebug } from '../../debug.js';
import { dentalWeights } from '../../core/dentalShading.js';
import { h } from './dom.js';
import { labelEntries, partAt, placeLabels, preferredAngles } from './labelPlacement.js';
import './labels.css';

const SVG = 'http://www.w3.org/2000/svg';
/** Meshes never named by a pointer: the skin is see-through, the air is no part. */
const SKIN_TISSUES = new Set( [ 'skin', 'shell' ] );
const SKIPPED_ROLES = new Set( [ 'air' ] );
/** Tissues that hide what lies behind them from the camera: bone and teeth. */
const BONE_TISSUES = new Set( [ 'maxilla', 'mandible', 'bone', 'solidBone' ] );
/** How far short of a label's point a hit must be to hide it, mm: the point lies on a surface. */
const COVER_MARGIN_MM = 3;

export class LabelLayer {

	/**
	 * @param {{ document: object, head: object, viewer: object, stage: HTMLElement,
	 *   obstacles?: () => Array<Element|null> }} options the landmarks document, the head whose
	 *   meshes are pointed at, the viewer, the element the overlay covers, and more elements the
	 *   labels must keep off (the stage's own other children always are)
	 */
	constructor( { document, head, viewer, stage, obstacles = () => [] } ) {

		this.entries = labelEntries( document );
		this.obstacles = obstacles;
		this.overlapping = 0;
		this.head = head;
		this.viewer = viewer;
		this.stage = stage;
		this.visible = false;
		this.hovered = null;
		this.raycaster = new Raycaster();
		this.sightline = new Raycaster();
		this.pointer = new Vector2();
		this.teeth = new Map();

		this.svg = window.document.createElementNS( SVG, 'svg' );
		this.svg.setAttribute( 'class', 'label-lines' );
		this.svg.setAttribute( 'aria-hidden', 'true' );
		this.labels = this.entries.map( ( entry ) => {

			const line = window.document.createElementNS( SVG, 'line' );
			const dot = window.document.createElementNS( SVG, 'circle' );
			dot.setAttribute( 'r', '5' );
			line.setAttribute( 'class', `label-line label-${ entry.kind }` );
			dot.setAttribute( 'class', `label-dot label-${ entry.kind }` );
			this.svg.append( line, dot );
			const text = h( 'span', { className: `label label-${ entry.kind }`, 'data-landmark': entry.name }, entry.label );
			return { entry, line, dot, text };

		} );
		this.tip = h( 'div', { className: 'label-hover', role: 'status', 'aria-live': 'polite', hidden: '' } );
		this.element = h( 'div', { className: 'label-layer', hidden: '' }, this.svg, ...this.labels.map( ( l ) => l.text ) );
		stage.append( this.element, this.tip );

		const canvas = viewer.renderer.domElement;
		this.onPointer = ( event ) => this.pointAt( event );
		this.onLeave = () => this.setHovered( null );
		canvas.addEventListener( 'pointermove', this.onPointer );
		canvas.addEventListener( 'pointerdown', this.onPointer );
		canvas.addEventListener( 'pointerleave', this.onLeave );
		/** The camera matrix and canvas size the labels were last laid out for. */
		this.seenView = new Float64Array( 18 ).fill( Number.NaN );
		this.cleanups = [
			() => canvas.removeEventListener( 'pointermove', this.onPointer ),
			() => canvas.removeEventListener( 'pointerdown', this.onPointer ),
			() => canvas.removeEventListener( 'pointerleave', this.onLeave ),
			viewer.onFrame( () => {

				if ( this.visible && this.viewChanged() ) this.layout();
				return false; // the labels are HTML over the canvas: they never need a new 3D frame

			} ),
			registerDebug( 'labels', () => ( { visible: this.visible, count: this.visible ? this.shown.length : 0, names: this.visible ? this.shown.map( ( label ) => label.entry.name ) : [], hidden: this.visible ? this.hiddenLabels() : [], hovered: this.hovered, overlapping: this.visible ? this.overlapping : 0 } ) ),
		];

	}

	/**
	 * Show every label (true), none (false), or only those named (landmark names, as a lesson
	 * item lists them: the place and the articulator).
	 */
	setVisible( on ) {

		const only = Array.isArray( on ) ? new Set( on ) : null;
		this.visible = Boolean( on ) && ( ! only || only.size > 0 );
		for ( const label of this.labels ) {

			label.shown = ! only || only.has( label.entry.name );
			label.text.hidden = ! label.shown;
			label.line.style.display = label.dot.style.display = label.shown ? '' : 'none';

		}

		this.element.hidden = ! this.visible;
		if ( this.visible ) this.layout();

	}

	/** The labels on show. */
	get shown() {

		return this.labels.filter( ( label ) => label.shown !== false );

	}

	/** True when the camera or the canvas size changed since the last call (then labels move). */
	viewChanged() {

		const matrix = this.viewer.camera.matrixWorld.elements;
		const canvas = this.viewer.renderer.domElement;
		const seen = this.seenView;
		let changed = false;
		for ( let k = 0; k < 16; k ++ ) {

			if ( seen[ k ] !== matrix[ k ] ) changed = true;
			seen[ k ] = matrix[ k ];

		}

		if ( seen[ 16 ] !== canvas.clientWidth || seen[ 17 ] !== canvas.clientHeight ) changed = true;
		seen[ 16 ] = canvas.clientWidth;
		seen[ 17 ] = canvas.clientHeight;
		return changed;

	}

	/** Put every label on show at its landmark on the screen, keeping labels apart. */
	layout() {

		const rect = this.stage.getBoundingClientRect();
		const canvasRect = this.viewer.renderer.domElement.getBoundingClientRect();
		const v = new Vector3();
		const labels = this.shown;
		const entries = labels.map( ( label ) => label.entry );
		const points = labels.map( ( { entry } ) => {

			v.fromArray( entry.position ).project( this.viewer.camera );
			return { x: ( v.x + 1 ) / 2 * canvasRect.width + canvasRect.left - rect.left, y: ( 1 - v.y ) / 2 * canvasRect.height + canvasRect.top - rect.top };

		} );
		const angles = preferredAngles( entries, points );
		const anchors = labels.map( ( label, i ) => {

			label.size ??= { w: label.text.offsetWidth, h: label.text.offsetHeight };
			return { ...points[ i ], ...label.size, angle: angles[ i ] };

		} );
		// Places first (they are read in order along the roof), then the parts.
		const order = anchors.map( ( _, i ) => i ).sort( ( a, b ) => ( entries[ a ].kind === 'place' ? 0 : 1 ) - ( entries[ b ].kind === 'place' ? 0 : 1 ) );
		const boxes = placeLabels( order.map( ( i ) => anchors[ i ] ), { width: rect.width, height: rect.height }, this.obstacleRects( rect ) );
		this.overlapping = boxes.filter( ( box ) => box.overlapping ).length;
		this.svg.setAttribute( 'viewBox', `0 0 ${ rect.width } ${ rect.height }` );
		order.forEach( ( i, k ) => {

			const { line, dot, text } = labels[ i ];
			const box = boxes[ k ];
			const p = points[ i ];
			text.style.transform = `translate(${ box.x }px, ${ box.y }px)`;
			dot.setAttribute( 'cx', p.x );
			dot.setAttribute( 'cy', p.y );
			line.setAttribute( 'x1', p.x );
			line.setAttribute( 'y1', p.y );
			line.setAttribute( 'x2', Math.min( Math.max( p.x, box.x ), box.x + box.w ) );
			line.setAttribute( 'y2', Math.min( Math.max( p.y, box.y ), box.y + box.h ) );

		} );

	}

	/** The screen rectangles of the panels the labels keep off, in the stage's frame (CSS px). */
	obstacleRects( stageRect ) {

		const canvas = this.viewer.renderer.domElement;
		const elements = [ ...this.stage.children ].filter( ( el ) => el !== this.element && el !== this.tip && el !== canvas );
		const rects = [];
		for ( const el of [ ...elements, ...this.obstacles() ] ) {

			if ( ! el || el.hidden ) continue;
			const r = el.getBoundingClientRect();
			const x = r.left - stageRect.left, y = r.top - stageRect.top;
			// Only what reaches into the stage matters.
			if ( r.width === 0 || r.height === 0 || x >= stageRect.width || y >= stageRect.height || x + r.width <= 0 || y + r.height <= 0 ) continue;
			rects.push( { x, y, w: r.width, h: r.height } );

		}

		return rects;

	}

	/**
	 * The names of the labels on show whose point the camera cannot see: bone or teeth lie
	 * between (cut away with the cutaway; the skin too when it is opaque), the part the label
	 * itself names aside. A lesson that names the tongue tip in a view where the jaw hides it
	 * shows nothing it teaches.
	 */
	hiddenLabels() {

		const head = this.head;
		const opaqueSkin = ! head.transparency && ! head.cutaway;
		const blockers = [];
		for ( const part of head.parts.values() ) {

			if ( ! part.group.visible || ! ( BONE_TISSUES.has( part.tissue ) || ( opaqueSkin && SKIN_TISSUES.has( part.tissue ) ) ) ) continue;
			for ( const mesh of part.meshes ) if ( mesh.visible && ! mesh.userData.skinPass?.match( /back|prepass/ ) ) blockers.push( { mesh, part: part.name } );

		}

		const eye = this.viewer.camera.getWorldPosition( new Vector3() );
		const direction = new Vector3();
		return this.shown.filter( ( { entry } ) => {

			const own = new Set( entry.meshes );
			const meshes = blockers.filter( ( b ) => ! own.has( b.part ) ).map( ( b ) => b.mesh );
			direction.fromArray( entry.position ).sub( eye );
			const distance = direction.length();
			this.sightline.set( eye, direction.normalize() );
			this.sightline.far = Math.max( distance - COVER_MARGIN_MM, 0 );
			return this.sightline.intersectObjects( meshes, false ).some( ( hit ) => ! head.cutaway || hit.point.z >= - 1e-3 );

		} ).map( ( { entry } ) => entry.name );

	}

	/** Name the part under a pointer event (hover or tap). */
	pointAt( event ) {

		const rect = this.viewer.renderer.domElement.getBoundingClientRect();
		this.pointer.set( ( event.clientX - rect.left ) / rect.width * 2 - 1, - ( ( event.clientY - rect.top ) / rect.height ) * 2 + 1 );
		this.setHovered( this.partAtPointer(), event.clientX - this.stage.getBoundingClientRect().left, event.clientY - this.stage.getBoundingClientRect().top );

	}

	/** { name, label } of the part under this.pointer, or null. */
	partAtPointer() {

		const head = this.head;
		const seeThrough = head.transparency > 0 || head.cutaway;
		const meshes = [];
		for ( const part of head.parts.values() ) {

			if ( SKIPPED_ROLES.has( part.role ) || ! part.group.visible ) continue;
			if ( SKIN_TISSUES.has( part.tissue ) && seeThrough ) continue;
			meshes.push( ...part.meshes.filter( ( mesh ) => mesh.visible && ! mesh.userData.skinPass?.match( /back|prepass/ ) ) );

		}

		this.raycaster.setFromCamera( this.pointer, this.viewer.camera );
		const hits = this.raycaster.intersectObjects( meshes, false ).filter( ( hit ) => ! head.cutaway || hit.point.z >= - 1e-3 );
		if ( ! hits.length ) return null;
		const hit = hits[ 0 ];
		const name = hit.object.name;
		const part = head.parts.get( name ) ?? head.parts.get( name.split( ':' )[ 0 ] );
		if ( ! part || SKIN_TISSUES.has( part.tissue ) ) return null;
		return partAt( part.name, hit.point.toArray(), this.entries, { isTooth: this.isTooth( part, hit ) } );

	}

	/** Whether the hit lies on a tooth (the head view's own tooth rule), null off the jaws. */
	isTooth( part, hit ) {

		if ( part.tissue !== 'maxilla' && part.tissue !== 'mandible' ) return null;
		if ( ! this.teeth.has( part.name ) ) {

			const positions = part.geometry.getAttribute( 'position' ).array;
			const teeth = new Float32Array( positions.length / 3 );
			const gum = new Float32Array( positions.length / 3 );
			const maxilla = [ ...this.head.parts.values() ].find( ( p ) => p.tissue === 'maxilla' );
			let occlusalY;
			if ( maxilla ) {

				const y = maxilla.geometry.getAttribute( 'position' ).array;
				occlusalY = Infinity;
				for ( let i = 1; i < y.length; i += 3 ) occlusalY = Math.min( occlusalY, y[ i ] );

			}

			const options = part.tissue === 'mandible' ? { upward: true, occlusalY } : {};
			try {

				dentalWeights( Float32Array.from( positions ), options, teeth, gum );

			} catch {

				teeth.fill( 0 );

			}

			this.teeth.set( part.name, teeth );

		}

		const teeth = this.teeth.get( part.name );
		const { a, b, c } = hit.face;
		return Math.max( teeth[ a ], teeth[ b ], teeth[ c ] ) > 0.5;

	}

	setHovered( part, x = 0, y = 0 ) {

		this.hovered = part ? part.label : null;
		this.tip.hidden = ! part;
		if ( part ) {

			this.tip.textContent = part.label;
			this.tip.style.transform = `translate(${ x + 18 }px, ${ y - 14 }px)`;

		}

	}

	dispose() {

		for ( const cleanup of this.cleanups ) cleanup();
		this.element.remove();
		this.tip.remove();

	}

}
