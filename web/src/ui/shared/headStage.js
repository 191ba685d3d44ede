// The 3D stage every view starts from: a viewer in the given element, with the head in its
// scene, and a clear message (through ``fail``) when WebGL2 is missing or the context is lost.
import { Viewer } from '../../scene/Viewer.js';
import { Head } from '../../scene/Head.js';

/** Returns { viewer, head }, or null after calling ``fail`` when the browser has no WebGL2. */
export function createHeadStage( element, fail ) {

	let viewer;
	try {

		viewer = new Viewer( element );

	} catch ( error ) {

		fail( `This browser cannot show the 3D view (WebGL2 is needed): ${ error.message }` );
		return null;

	}

	viewer.renderer.domElement.addEventListener( 'webglcontextlost', ( event ) => {

		event.preventDefault();
		fail( 'The 3D view stopped because the graphics driver was reset. Reload the page to continue.' );

	} );
	const head = new Head();
	viewer.scene.add( head.group );
	return { viewer, head };

}
