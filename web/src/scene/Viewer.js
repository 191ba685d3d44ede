// The renderer, camera, controls, lights and render loop. Scene content (the head, later the
// tongue and EPG dots) is added to `viewer.scene` by its owners, who also hook into the loop with
// `viewer.onFrame( fn )`.

import {
	Color,
	DirectionalLight,
	HemisphereLight,
	PerspectiveCamera,
	Scene,
	SRGBColorSpace,
	Vector3,
	WebGLRenderer,
} from 'three';
import { OrbitControls } from 'three/addons/controls/OrbitControls.js';
import { easeInOut, interpolatePose } from './viewPresets.js';
import { FrameTimer } from './FrameTimer.js';
import { attachKeyboardOrbit } from './keyboardOrbit.js';
import { registerDebug } from '../debug.js';
import { pageRendererName, rendererOptions } from './rendererChoice.js';

export const BACKGROUND_COLOR = '#dfe3e8';

const BOX_CORNERS = Array.from( { length: 8 }, () => new Vector3() );
const SCRATCH_POINT = new Vector3();

export class Viewer {

	/**
	 * container: the element the canvas fills. Throws if WebGL2 is unavailable.
	 */
	constructor( container, { fov = 30 } = {} ) {

		this.container = container;
		const rendererName = pageRendererName();
		const options = rendererOptions( rendererName );
		this.renderer = new WebGLRenderer( options );
		this.renderer.outputColorSpace = SRGBColorSpace;
		this.renderer.localClippingEnabled = true;
		this.renderer.setPixelRatio( Math.min( window.devicePixelRatio || 1, 2 ) );
		this.renderer.domElement.className = 'viewer-canvas';
		this.renderer.domElement.setAttribute( 'aria-label', '3D view of the head' );
		this.renderer.domElement.setAttribute( 'aria-description', 'Arrow keys turn the head, + and − zoom' );
		this.renderer.domElement.setAttribute( 'role', 'img' );
		container.appendChild( this.renderer.domElement );

		this.scene = new Scene();
		this.scene.background = new Color( BACKGROUND_COLOR );

		// Millimetres: the head is about 200 mm across.
		this.camera = new PerspectiveCamera( fov, 1, 5, 5000 );
		this.camera.position.set( 600, 50, 0 );
		this.scene.add( this.camera );
		this.addLights();

		this.controls = new OrbitControls( this.camera, this.renderer.domElement );
		this.controls.enableDamping = true;
		this.controls.dampingFactor = 0.12;
		this.controls.zoomToCursor = true; // point at the teeth and zoom in on them
		this.controls.minDistance = 80;
		this.controls.maxDistance = 2000;
		this.controls.addEventListener( 'change', () => this.requestRender() );
		this.controls.addEventListener( 'start', () => {

			this.flight = null;

		} );
		this.detachKeys = attachKeyboardOrbit( this );
		// Where the camera is: tests of the keyboard and of the views read it.
		this.unregisterCamera = registerDebug( 'camera', () => ( {
			position: this.camera.position.toArray(), target: this.controls.target.toArray(),
		} ) );
		this.unregisterRenderer = registerDebug( 'renderer', () => ( { name: rendererName, antialias: options.antialias } ) );

		this.frameHooks = new Set();
		this.timer = new FrameTimer( 60 );
		this.frameCount = 0;
		this.flight = null;
		this.lastTime = null;
		this.lastRenderTime = null;
		this.dirty = true;

		this.resizeObserver = new ResizeObserver( () => this.resize() );
		this.resizeObserver.observe( container );
		this.resize();

		this.renderer.setAnimationLoop( ( time ) => this.frame( time ) );

	}

	/** Soft light that follows the camera, so every view is lit from the viewer's side. */
	addLights() {

		this.scene.add( new HemisphereLight( '#ffffff', '#8a7f78', 1.6 ) );

		const key = new DirectionalLight( '#fff6ee', 1.9 );
		key.position.set( - 0.6, 0.9, 1 );
		const fill = new DirectionalLight( '#e8eeff', 0.8 );
		fill.position.set( 1, 0.1, 0.6 );
		const rim = new DirectionalLight( '#ffffff', 0.6 );
		rim.position.set( 0, 0.6, - 1 );
		for ( const light of [ key, fill, rim ] ) {

			// A directional light shines from its position toward its target; both ride on the camera.
			light.target.position.set( 0, 0, 0 );
			this.camera.add( light, light.target );

		}

	}

	/** WebGL2 is required by three.js; reports what the renderer really got. */
	get webgl2() {

		const gl = this.renderer.getContext();
		return typeof WebGL2RenderingContext !== 'undefined' && gl instanceof WebGL2RenderingContext;

	}

	/** Median time between recent consecutive drawn frames, in ms (null until something has moved). */
	get frameTimeMs() {

		return this.timer.median();

	}

	/** True while the camera is flying to a view. */
	get animating() {

		return this.flight !== null;

	}

	/**
	 * Call fn( dtSeconds, timeSeconds ) on every tick of the loop, before drawing. While a hook is
	 * registered the scene is drawn every frame, unless the hook returns false (nothing changed).
	 * Returns a function that removes the hook.
	 */
	onFrame( fn ) {

		this.frameHooks.add( fn );
		return () => this.frameHooks.delete( fn );

	}

	/** Fly the camera to pose { position, target } ([x, y, z] arrays) in durationMs. */
	flyTo( pose, durationMs = 700 ) {

		const from = {
			position: this.camera.position.toArray(),
			target: this.controls.target.toArray(),
		};
		if ( durationMs <= 0 ) {

			this.applyPose( pose );
			this.flight = null;
			return;

		}

		this.flight = { from, to: pose, start: null, duration: durationMs, current: { position: [ 0, 0, 0 ], target: [ 0, 0, 0 ] } };

	}

	applyPose( pose ) {

		this.camera.position.fromArray( pose.position );
		this.controls.target.fromArray( pose.target );
		this.camera.lookAt( this.controls.target );

	}

	resize() {

		const width = Math.max( 1, this.container.clientWidth );
		const height = Math.max( 1, this.container.clientHeight );
		this.renderer.setSize( width, height, false );
		this.camera.aspect = width / height;
		this.camera.updateProjectionMatrix();
		this.requestRender();

	}

	get aspect() {

		return this.camera.aspect;

	}

	/**
	 * The CSS-pixel rectangle on the canvas covered by the world-space box (THREE.Box3), or null if
	 * it is behind the camera.
	 */
	screenRect( box ) {

		// Scratch corners: the EPG card's placement asks for the lips' rectangle as the view moves.
		BOX_CORNERS.forEach( ( corner, i ) => corner.set( i & 1 ? box.max.x : box.min.x, i & 2 ? box.max.y : box.min.y, i & 4 ? box.max.z : box.min.z ) );
		return this.screenRectOfPoints( BOX_CORNERS );

	}

	/** The CSS-pixel rectangle on the page covering world-space points (Vector3s), or null if one is behind the camera. */
	screenRectOfPoints( points ) {

		const projected = SCRATCH_POINT;
		let x0 = Infinity, y0 = Infinity, x1 = - Infinity, y1 = - Infinity;
		for ( const point of points ) {

			projected.copy( point ).project( this.camera );
			if ( projected.z > 1 ) return null;
			x0 = Math.min( x0, projected.x ); x1 = Math.max( x1, projected.x );
			y0 = Math.min( y0, projected.y ); y1 = Math.max( y1, projected.y );

		}

		const rect = this.renderer.domElement.getBoundingClientRect();
		const left = ( x0 + 1 ) / 2 * rect.width + rect.left;
		const right = ( x1 + 1 ) / 2 * rect.width + rect.left;
		const top = ( 1 - y1 ) / 2 * rect.height + rect.top;
		const bottom = ( 1 - y0 ) / 2 * rect.height + rect.top;
		return { x: left, y: top, width: right - left, height: bottom - top };

	}

	/** Draw the next frame (after a change to the scene made outside a frame hook). */
	requestRender() {

		this.dirty = true;

	}

	/** True while a change waits to be drawn. */
	get renderPending() {

		return this.dirty;

	}

	/**
	 * One tick of the loop. The scene is drawn only when something changed: a camera move, a
	 * requestRender(), or a frame hook that did not return false. A still head costs no GPU time,
	 * which matters on tablets and on software-rendered test machines.
	 */
	frame( timeMs ) {

		const dt = this.lastTime === null ? 0 : ( timeMs - this.lastTime ) / 1000;
		this.lastTime = timeMs;

		if ( this.flight ) {

			this.advanceFlight( timeMs );
			this.dirty = true;

		}

		this.controls.update(); // emits 'change' (and so requests a render) while damping moves the camera
		for ( const hook of this.frameHooks ) {

			if ( hook( dt, timeMs / 1000 ) !== false ) this.dirty = true;

		}

		if ( ! this.dirty ) {

			this.lastRenderTime = null;
			return;

		}

		this.dirty = false;
		this.renderer.render( this.scene, this.camera );
		this.frameCount ++;
		// Frame time: the interval between consecutive drawn frames (while something moves).
		if ( this.lastRenderTime !== null ) this.timer.add( timeMs - this.lastRenderTime );
		this.lastRenderTime = timeMs;

	}

	advanceFlight( timeMs ) {

		const flight = this.flight;
		if ( flight.start === null ) flight.start = timeMs;
		const s = Math.min( 1, ( timeMs - flight.start ) / flight.duration );
		interpolatePose( flight.from, flight.to, easeInOut( s ), flight.current );
		this.applyPose( flight.current );
		if ( s >= 1 ) this.flight = null;

	}

	dispose() {

		this.renderer.setAnimationLoop( null );
		this.detachKeys();
		this.unregisterCamera();
		this.unregisterRenderer();
		this.resizeObserver.disconnect();
		this.controls.dispose();
		this.renderer.dispose();
		this.renderer.domElement.remove();

	}

}
