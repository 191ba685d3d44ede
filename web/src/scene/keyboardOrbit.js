// The keyboard for the 3D view: the canvas takes focus (Tab or a click), then the arrow keys turn
// the camera about the orbit target and + and − zoom, so the head can be looked at without a
// mouse. OrbitControls' own keys pan rather than rotate, so they stay off. One press turns the
// camera by ROTATE_STEP_DEG (with Shift, by four times that), or moves it ZOOM_FACTOR closer
// or farther, within the controls' distance limits.

import { Spherical, Vector3 } from 'three';

/** One arrow press: the camera's turn about the target, degrees (Shift: four times). */
export const ROTATE_STEP_DEG = 10;
/** One + or − press: the camera's distance is divided or multiplied by this. */
export const ZOOM_FACTOR = 1.15;
/** The polar angle keeps this far from the poles, radians (the view never flips over). */
const POLE_MARGIN = 0.05;

/** The change a key asks for: { theta, phi } in radians, { zoom } as a factor, or null. */
export function keyMove( key, shift = false ) {

	const step = ROTATE_STEP_DEG * ( shift ? 4 : 1 ) * Math.PI / 180;
	switch ( key ) {

		case 'ArrowLeft': return { theta: - step };
		case 'ArrowRight': return { theta: step };
		case 'ArrowUp': return { phi: - step };
		case 'ArrowDown': return { phi: step };
		case '+': case '=': case 'Add': return { zoom: 1 / ZOOM_FACTOR };
		case '-': case '_': case 'Subtract': return { zoom: ZOOM_FACTOR };
		default: return null;

	}

}

/**
 * Make the viewer's canvas focusable and steer its camera from the keyboard. Returns a function
 * that removes the listener.
 * @param {import('./Viewer.js').Viewer} viewer
 */
export function attachKeyboardOrbit( viewer ) {

	const canvas = viewer.renderer.domElement;
	canvas.tabIndex = 0;
	canvas.setAttribute( 'aria-keyshortcuts', 'ArrowLeft ArrowRight ArrowUp ArrowDown + -' );
	const offset = new Vector3();
	const spherical = new Spherical();

	const onKey = ( event ) => {

		if ( event.altKey || event.ctrlKey || event.metaKey ) return;
		const move = keyMove( event.key, event.shiftKey );
		if ( ! move ) return;
		event.preventDefault();
		const { camera, controls } = viewer;
		viewer.flight = null;
		offset.copy( camera.position ).sub( controls.target );
		spherical.setFromVector3( offset );
		spherical.theta += move.theta ?? 0;
		spherical.phi = Math.min( Math.PI - POLE_MARGIN, Math.max( POLE_MARGIN, spherical.phi + ( move.phi ?? 0 ) ) );
		spherical.radius = Math.min( controls.maxDistance, Math.max( controls.minDistance, spherical.radius * ( move.zoom ?? 1 ) ) );
		offset.setFromSpherical( spherical );
		camera.position.copy( controls.target ).add( offset );
		camera.lookAt( controls.target );
		viewer.requestRender();

	};

	canvas.addEventListener( 'keydown', onKey );
	return () => canvas.removeEventListener( 'keydown', onKey );

}
