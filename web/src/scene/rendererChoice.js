// Which WebGL renderer the browser gives, and whether to ask it for multisampling. A software
// rasteriser (SwiftShader, llvmpipe, Microsoft's Basic Render Driver: what a school machine with
// a blocklisted or missing GPU falls back to) pays for 4x multisampling on every pixel of every
// frame, about a third of its time for this scene; there the edges are left unsmoothed so that
// the head stays responsive.

const SOFTWARE_RENDERERS = /swiftshader|llvmpipe|softpipe|software|basic render driver/i;

/** True when a WebGL renderer name (UNMASKED_RENDERER_WEBGL) names a software rasteriser. */
export function isSoftwareRenderer( name ) {

	return typeof name === 'string' && SOFTWARE_RENDERERS.test( name );

}

/**
 * The unmasked renderer name of a throwaway WebGL2 context, or null when the browser hides it or
 * has no WebGL2 (the Viewer then reports its own error). The context is released at once.
 */
export function probeRendererName( doc = globalThis.document ) {

	const gl = doc?.createElement( 'canvas' ).getContext( 'webgl2' );
	if ( ! gl ) return null;
	const info = gl.getExtension( 'WEBGL_debug_renderer_info' );
	const name = info ? gl.getParameter( info.UNMASKED_RENDERER_WEBGL ) : gl.getParameter( gl.RENDERER );
	gl.getExtension( 'WEBGL_lose_context' )?.loseContext();
	return typeof name === 'string' ? name : null;

}

let pageRenderer;

/**
 * The page's renderer name, probed once: every Viewer of the page (one per view the user opens)
 * gets the same GPU, so later views make no throwaway context.
 */
export function pageRendererName() {

	if ( pageRenderer === undefined ) pageRenderer = probeRendererName();
	return pageRenderer;

}

/** The WebGLRenderer options for a renderer name: multisampling unless it is software. */
export function rendererOptions( name ) {

	return { antialias: ! isSoftwareRenderer( name ), stencil: true, powerPreference: 'high-performance' };

}
