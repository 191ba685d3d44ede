// Whether the Viewer asks for multisampling (web/src/scene/rendererChoice.js).
import { test } from 'node:test';
import assert from 'node:assert/strict';

import { isSoftwareRenderer, pageRendererName, probeRendererName, rendererOptions } from '../../web/src/scene/rendererChoice.js';

test( 'software rasterisers are recognised by their renderer names', () => {

	for ( const name of [
		'ANGLE (Google, Vulkan 1.3.0 (SwiftShader Device (Subzero) (0x0000C0DE)), SwiftShader driver)',
		'Google SwiftShader',
		'llvmpipe (LLVM 15.0.6, 256 bits)',
		'ANGLE (Microsoft, Microsoft Basic Render Driver Direct3D11 vs_5_0 ps_5_0, D3D11)',
		'Mesa softpipe',
	] ) assert.equal( isSoftwareRenderer( name ), true, name );

} );

test( 'hardware renderers and hidden names keep multisampling', () => {

	for ( const name of [
		'ANGLE (Intel, Intel(R) UHD Graphics 620 Direct3D11 vs_5_0 ps_5_0, D3D11)',
		'ANGLE (Apple, ANGLE Metal Renderer: Apple M1, Unspecified Version)',
		'Mali-G52',
		'WebKit WebGL',
		null,
		undefined,
	] ) {

		assert.equal( isSoftwareRenderer( name ), false, String( name ) );
		assert.equal( rendererOptions( name ).antialias, true, String( name ) );

	}
	assert.equal( rendererOptions( 'Google SwiftShader' ).antialias, false );
	assert.equal( rendererOptions( 'Google SwiftShader' ).stencil, true );

} );

test( 'the probe reads the unmasked name, releases its context, and answers null without WebGL2', () => {

	let lost = false;
	const gl = {
		RENDERER: 0x1F01,
		getExtension: ( name ) => ( name === 'WEBGL_debug_renderer_info' ? { UNMASKED_RENDERER_WEBGL: 0x9246 }
			: name === 'WEBGL_lose_context' ? { loseContext: () => ( lost = true ) } : null ),
		getParameter: ( key ) => ( key === 0x9246 ? 'Google SwiftShader' : 'WebKit WebGL' ),
	};
	const doc = ( context ) => ( { createElement: () => ( { getContext: () => context } ) } );
	assert.equal( probeRendererName( doc( gl ) ), 'Google SwiftShader' );
	assert.equal( lost, true );
	assert.equal( probeRendererName( doc( null ) ), null );
	assert.equal( probeRendererName( undefined ), null );

} );

test( 'the page is probed once, however many views make a Viewer', () => {

	let contexts = 0;
	const gl = { RENDERER: 0x1F01, getExtension: () => null, getParameter: () => 'Google SwiftShader' };
	const saved = globalThis.document;
	globalThis.document = { createElement: () => ( { getContext: () => ( contexts ++, gl ) } ) };
	try {

		assert.equal( pageRendererName(), 'Google SwiftShader' );
		assert.equal( pageRendererName(), 'Google SwiftShader' );
		assert.equal( contexts, 1 );

	} finally {

		globalThis.document = saved;

	}

} );
