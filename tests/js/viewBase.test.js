// The base of every view (web/src/ui/shared/View.js), without a browser: what a view mounts is
// undone by unmount(), in order, and the stage goes after what the view holds.
import { test } from 'node:test';
import assert from 'node:assert/strict';

import { debugObject } from '../../web/src/debug.js';
import { View } from '../../web/src/ui/shared/View.js';

/** An event target that keeps its listeners. */
function target() {

	const listeners = new Map();
	return {
		listeners,
		addEventListener: ( type, handler ) => listeners.set( type, handler ),
		removeEventListener: ( type, handler ) => listeners.get( type ) === handler && listeners.delete( type ),
	};

}

test( 'unmount runs the clean-ups in order, then dispose, then the stage, and takes the element out', () => {

	const steps = [];
	class Probe extends View {

		mount( container ) {

			this.attach( container, { remove: () => steps.push( 'root removed' ) } );
			this.debugFields( { probeState: () => ( { mounted: true } ) } );
			this.listen( this.window, 'keydown', () => {} );
			this.onUnmount( () => steps.push( 'first clean-up' ), () => steps.push( 'second clean-up' ) );
			this.viewer = { dispose: () => steps.push( 'viewer disposed' ) };
			this.head = { dispose: () => steps.push( 'head disposed' ) };
			return this;

		}

		dispose() {

			steps.push( 'dispose' );

		}

	}

	const appended = [];
	const win = target();
	const view = new Probe( { api: { name: 'fake' }, win } ).mount( { append: ( element ) => appended.push( element ) } );
	assert.equal( appended[ 0 ], view.root );
	assert.equal( view.api.name, 'fake' );
	assert.deepEqual( debugObject().probeState, { mounted: true } );
	assert.ok( win.listeners.has( 'keydown' ) );
	view.unmount();
	assert.deepEqual( steps, [ 'first clean-up', 'second clean-up', 'dispose', 'viewer disposed', 'head disposed', 'root removed' ] );
	assert.equal( debugObject().probeState, undefined );
	assert.equal( win.listeners.size, 0 );
	assert.equal( view.viewer, null, 'a load still under way sees the view is gone' );
	view.unmount();
	assert.equal( steps.filter( ( step ) => step === 'first clean-up' ).length, 1, 'clean-ups run once' );

} );

test( 'the stage debug fields read the viewer while there is one', () => {

	const view = new View( { win: target() } );
	const fields = view.stageDebugFields();
	assert.deepEqual( Object.fromEntries( Object.entries( fields ).map( ( [ k, get ] ) => [ k, get() ] ) ), { frames: 0, frameTimeMs: null, cameraMoving: false, renderPending: false } );
	view.viewer = { frameCount: 3, frameTimeMs: 1.5, animating: true, renderPending: true };
	assert.deepEqual( Object.fromEntries( Object.entries( fields ).map( ( [ k, get ] ) => [ k, get() ] ) ), { frames: 3, frameTimeMs: 1.5, cameraMoving: true, renderPending: true } );

} );
