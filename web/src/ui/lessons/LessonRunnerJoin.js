// How children join a class, for the teacher to show: the class code in large letters, a QR code
// of the join link, and the link itself; "Show to the class" puts them full screen for a
// projector. The link is on the school's address (GET /site: GLASSHEAD_PUBLIC_URL), else on
// this page's own; when that is this computer's own (localhost), the card says tablets cannot
// reach it and what sets the school's address. A tablet that opens the link lands on the class's
// pictures (#/practice?code=…): no code to type.

import { h } from '../shared/dom.js';
import { qrSvg } from '../shared/qrCode.js';

/** The join link of class `code` on the site at `base` (no trailing slash). */
export function joinLink( base, code ) {

	return `${ base }/#/practice?code=${ encodeURIComponent( code ) }`;

}

/** A class code as it is read out and typed: two groups of three ('ACD 347'). */
export function spacedCode( code ) {

	return String( code ).replace( /^(.{3})(.+)$/, '$1 $2' );

}

/** Where the site is: the school's address when the server has one, else this page's. */
export function siteBase( publicUrl, location = globalThis.location ) {

	if ( publicUrl ) return publicUrl.replace( /\/+$/, '' );
	const path = location.pathname.replace( /index\.html$/, '' ).replace( /\/+$/, '' );
	return `${ location.origin }${ path }`;

}

/** Whether `base` is this computer's own address, which no tablet can reach. */
export function isLoopbackAddress( base ) {

	let host;
	try {

		host = new URL( base ).hostname.replace( /^\[|\]$/g, '' );

	} catch {

		return false;

	}

	return host === 'localhost' || host.endsWith( '.localhost' ) || host === '::1' || /^127\./.test( host );

}

export class LessonRunnerJoin {

	/** @param {{ api: object, window?: Window }} options */
	constructor( { api, window = globalThis.window } ) {

		this.api = api;
		this.window = window;
		this.site = null;
		this.code = h( 'p', { className: 'lr-join-code', 'aria-label': 'Class code' } );
		this.qr = h( 'div', { className: 'lr-join-qr' } );
		this.link = h( 'a', { className: 'lr-join-link', target: '_blank', rel: 'noopener' } );
		this.warning = h( 'p', { className: 'lr-join-warning', role: 'note', hidden: '' },
			'This is this computer’s own address: tablets cannot reach it. Whoever runs Glasshead sets the school’s address (GLASSHEAD_PUBLIC_URL).' );
		this.showButton = h( 'button', { type: 'button', className: 'lr-join-show', onClick: () => this.showToClass() }, 'Show to the class' );
		this.element = h( 'section', { className: 'lr-join', 'aria-label': 'How children join', hidden: '' },
			h( 'p', { className: 'lr-join-label' }, 'Class code' ), this.code, this.qr,
			h( 'p', { className: 'lr-note' }, 'Scan it, or open ', this.link, ' and type the code.' ), this.warning, this.showButton );
		this.joined = null;

	}

	/** Show the way in to class `chosen` ({ name, join_code }), or nothing for null. */
	async show( chosen ) {

		this.element.hidden = ! chosen;
		if ( ! chosen ) return;
		this.site ??= this.api.get( 'site' ).catch( () => ( { public_url: null } ) );
		const base = siteBase( ( await this.site ).public_url, this.window.location );
		const link = joinLink( base, chosen.join_code );
		this.joined = { name: chosen.name, code: chosen.join_code, link, base, reachable: ! isLoopbackAddress( base ) };
		this.code.textContent = spacedCode( chosen.join_code );
		this.qr.replaceChildren( qrSvg( link, { label: `QR code of ${ link }`, document: this.window.document } ) );
		this.link.href = link;
		this.link.textContent = `${ base }/#/practice`;
		this.warning.hidden = this.joined.reachable;

	}

	/** The code and the QR code over the whole screen, for the class to read and scan; Esc or Close ends it. */
	showToClass() {

		const joined = this.joined;
		if ( ! joined ) return;
		const doc = this.window.document;
		const close = h( 'button', { type: 'button', className: 'lr-join-close' }, 'Close' );
		const dialog = h( 'dialog', { className: 'lr-join-dialog', 'aria-label': `How to join ${ joined.name }` },
			h( 'p', { className: 'lr-join-label' }, `${ joined.name }: class code` ),
			h( 'p', { className: 'lr-join-code lr-join-code-big' }, spacedCode( joined.code ) ),
			h( 'div', { className: 'lr-join-qr lr-join-qr-big' }, qrSvg( joined.link, { label: `QR code of ${ joined.link }`, document: doc } ) ),
			h( 'p', { className: 'lr-join-address' }, `${ joined.base }/#/practice` ), close );
		close.addEventListener( 'click', () => dialog.close() );
		dialog.addEventListener( 'close', () => dialog.remove() );
		doc.body.append( dialog );
		dialog.showModal();
		close.focus();

	}

	report() {

		return this.joined;

	}

}
