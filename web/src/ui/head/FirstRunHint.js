// The head view's first-run hint: one line on how to move the head, shown until the person
// dismisses it, and then never again in this browser (localStorage). Where storage is refused
// (private modes, a locked-down browser), the hint can still be closed for this page.
//
// hintDismissed( storage ) and dismissHint( storage ) are the pure part the unit tests read.

import { h } from '../shared/dom.js';

/** The key under which the dismissal is kept. */
export const HINT_KEY = 'glasshead.hint.head.dismissed';
/** What the hint says. */
export const HINT_TEXT = 'Drag to turn the head, pinch or scroll to zoom.';

/** Whether the hint was dismissed before (false when storage cannot be read). */
export function hintDismissed( storage ) {

	try {

		return storage?.getItem( HINT_KEY ) === '1';

	} catch {

		return false;

	}

}

/** Remember the dismissal; returns whether it was kept. */
export function dismissHint( storage ) {

	try {

		storage?.setItem( HINT_KEY, '1' );
		return storage ? hintDismissed( storage ) : false;

	} catch {

		return false;

	}

}

/**
 * The hint as an element to put over the 3D view, or null when it was dismissed before.
 * @param {{ storage?: Storage|null, onDismiss?: Function }} options
 */
export function createFirstRunHint( { storage = safeLocalStorage(), onDismiss = () => {} } = {} ) {

	if ( hintDismissed( storage ) ) return null;
	const element = h( 'aside', { className: 'first-run-hint', 'aria-label': 'Hint' },
		h( 'p', {}, HINT_TEXT ),
	);
	const close = h( 'button', { type: 'button', className: 'hint-close', onClick: () => {

		dismissHint( storage );
		element.remove();
		onDismiss();

	} }, 'Got it' );
	element.append( close );
	return element;

}

function safeLocalStorage() {

	try {

		return globalThis.localStorage ?? null;

	} catch {

		return null;

	}

}
