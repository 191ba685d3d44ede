// The way out of the child's kiosk, for a grown-up: a lock in the corner that must be held for
// HOLD_MS (a press and hold of the pointer, or of Enter or Space), with a ring filling while it
// is held. A tap says, in a picture and aloud, that a grown-up holds it.

import { h } from '../shared/dom.js';
import { picture } from '../shared/ChildPracticePictures.js';

/** How long a grown-up holds the lock to leave, ms. */
export const HOLD_MS = 2000;
/** What a tap on the lock says. */
export const GROWN_UP_LOCK = Object.freeze( { text: 'This is for grown-ups: they hold it to leave.', icon: 'ask-adult' } );

/** The lock button: `onLeave()` once held for HOLD_MS, `onTap()` when let go sooner. */
export function grownUpLock( onLeave, onTap, win = globalThis.window ) {

	let timer = null;
	let held = false;
	const button = h( 'button', { type: 'button', className: 'cp-lock', 'aria-label': `For grown-ups: hold for ${ HOLD_MS / 1000 } seconds to leave` }, picture( 'lock' ) );
	const start = ( event ) => {

		event.preventDefault();
		if ( timer !== null ) return;
		held = false;
		button.classList.add( 'cp-holding' );
		timer = win.setTimeout( () => {

			held = true;
			timer = null;
			button.classList.remove( 'cp-holding' );
			onLeave();

		}, HOLD_MS );

	};

	/** Let go before HOLD_MS: the ring empties; whether it was held long enough is returned. */
	const cancel = () => {

		if ( timer === null ) return true;
		win.clearTimeout( timer );
		timer = null;
		button.classList.remove( 'cp-holding' );
		return held;

	};
	const stop = () => {

		if ( ! cancel() ) onTap();

	};

	button.addEventListener( 'pointerdown', start );
	button.addEventListener( 'pointerup', stop );
	button.addEventListener( 'pointerleave', cancel );
	button.addEventListener( 'keydown', ( event ) => {

		if ( ( event.key === 'Enter' || event.key === ' ' ) && ! event.repeat ) start( event );
		else if ( event.key === 'Enter' || event.key === ' ' ) event.preventDefault();

	} );
	button.addEventListener( 'keyup', ( event ) => {

		if ( event.key === 'Enter' || event.key === ' ' ) stop();

	} );
	button.addEventListener( 'contextmenu', ( event ) => event.preventDefault() ); // a long touch opens no menu
	return button;

}
