// The admin's page (route `#/admin`): the people who sign in, added, renamed and removed here
// (AdminPeople.js); then every class with its children, and for each child an export of
// everything stored about them (GET /children/{id}/export, a JSON file) and its deletion
// (DELETE /children/{id}/data) after a confirmation on the page that says what goes. Only an
// admin may do any of it; anyone else sees who may and a link to sign in as them.

import { currentSession, onSessionChange } from '../../session.js';
import { AdminPeople } from './AdminPeople.js';
import { confirmWords, deletedWords, exportName } from './adminRows.js';
import { h } from '../shared/dom.js';
import { downloadFile } from '../shared/download.js';
import { signInPrompt } from '../shared/SignInPrompt.js';
import { hasRole } from '../shared/signIn.js';
import { View } from '../shared/View.js';
import './admin.css';

export class AdminView extends View {

	/** @param {{ api?: object, win?: Window, download?: Function }} options */
	constructor( { api, win, download = downloadFile } = {} ) {

		super( { api, win } );
		this.download = download;
		this.state = { screen: null, classes: [], children: [], exported: [], deleted: [], message: '', confirming: null };

	}

	mount( container ) {

		this.attach( container, h( 'div', { className: 'admin-view' } ) );
		this.onUnmount( onSessionChange( () => this.show() ) );
		this.debugFields( { admin: () => ( { ...this.state, people: this.people ? { ...this.people.state } : null } ) } );
		this.show();
		return this;

	}

	/** The page for whoever is signed in: the classes for an admin, a sign-in link otherwise. */
	show() {

		this.root.replaceChildren();
		const session = currentSession( { win: this.window } );
		this.heading = h( 'h1', { className: 'title' }, 'Admin' );
		if ( ! hasRole( session, [ 'admin' ] ) ) {

			this.state.screen = 'sign-in';
			const who = session?.kind === 'user' ? session.user : null;
			this.root.append( this.heading, who ? h( 'p', {}, `This page is for admins; you are signed in as ${ who.display_name || who.username } (${ who.role }).` ) : '',
				signInPrompt( { reason: 'as an admin', win: this.window } ) );
			return;

		}

		this.state.screen = 'classes';
		this.people = new AdminPeople( { api: this.api, me: () => currentSession( { win: this.window } )?.user?.id ?? null } );
		this.message = h( 'p', { className: 'status', role: 'status', 'aria-live': 'polite' }, 'Loading the classes…' );
		this.list = h( 'div', { className: 'admin-classes' } );
		this.root.append( this.heading, this.people.element,
			h( 'section', { className: 'admin-section', 'aria-labelledby': 'admin-privacy-title' }, h( 'h2', { id: 'admin-privacy-title' }, 'Privacy: children’s data' ),
				h( 'p', { className: 'admin-note' }, 'Export everything stored about a child as one JSON file, or delete it all. A deletion cannot be undone.' ),
				this.message, this.list ) );
		this.people.load();
		this.load();

	}

	say( text ) {

		this.state.message = text;
		this.message.textContent = text;

	}

	async load() {

		try {

			const [ classes, children ] = await Promise.all( [ this.api.get( 'classes?limit=1000' ), this.api.get( 'children?limit=1000' ) ] );
			this.state.classes = classes.classes.map( ( c ) => c.id );
			this.state.children = children.children.map( ( c ) => c.id );
			this.list.replaceChildren( ...classes.classes.map( ( schoolClass ) => this.classSection( schoolClass, children.children.filter( ( c ) => c.class_id === schoolClass.id ) ) ) );
			this.say( classes.classes.length ? '' : 'No classes yet.' );

		} catch ( error ) {

			this.fail( error );

		}

	}

	classSection( schoolClass, children ) {

		const rows = children.map( ( child ) => this.childRow( child ) );
		return h( 'section', { className: 'admin-class', 'aria-label': schoolClass.name },
			h( 'h2', {}, schoolClass.name, h( 'span', { className: 'admin-code' }, ` code ${ schoolClass.join_code }` ) ),
			rows.length ? h( 'ul', { className: 'admin-children', 'aria-label': `Children of ${ schoolClass.name }` }, ...rows ) : h( 'p', { className: 'admin-note' }, 'No children.' ) );

	}

	childRow( child ) {

		const confirmBox = h( 'div', { className: 'admin-confirm', role: 'alertdialog', 'aria-label': `Delete ${ child.display_name }’s data`, hidden: '' } );
		const row = h( 'li', { className: 'admin-child', 'data-child': String( child.id ) },
			h( 'span', { className: 'admin-name' }, `${ child.display_name } (${ child.avatar })` ),
			h( 'button', { type: 'button', 'aria-label': `Export everything about ${ child.display_name }`, onClick: () => this.exportChild( child ) }, 'Export everything (JSON)' ),
			h( 'button', { type: 'button', className: 'admin-danger', 'aria-label': `Delete everything about ${ child.display_name }…`, onClick: () => this.confirmDelete( child, confirmBox ) }, 'Delete everything…' ),
			confirmBox );
		return row;

	}

	async exportChild( child ) {

		try {

			const name = await this.download( `children/${ child.id }/export`, exportName( child ) );
			this.state.exported.push( child.id );
			this.say( `Saved ${ name }: everything stored about ${ child.display_name }.` );

		} catch ( error ) {

			this.fail( error );

		}

	}

	confirmDelete( child, box ) {

		this.state.confirming = child.id;
		const cancel = h( 'button', { type: 'button', onClick: () => {

			box.hidden = true;
			this.state.confirming = null;

		} }, 'Cancel' );
		box.replaceChildren( h( 'p', {}, confirmWords( child ) ),
			h( 'button', { type: 'button', className: 'admin-danger admin-really', onClick: () => this.deleteChild( child, box ) }, `Delete ${ child.display_name }’s data` ), cancel );
		box.hidden = false;
		cancel.focus();

	}

	async deleteChild( child, box ) {

		try {

			const counts = await this.api.delete( `children/${ child.id }/data` );
			this.state.deleted.push( child.id );
			this.state.confirming = null;
			this.state.children = this.state.children.filter( ( id ) => id !== child.id );
			box.closest( 'li' )?.remove();
			this.say( `Deleted everything about ${ child.display_name }: ${ deletedWords( counts ) }.` );

		} catch ( error ) {

			this.fail( error );

		}

	}

	fail( error ) {

		this.showFailure( error, this.message, ( words ) => this.say( words ) );

	}

}

/** Route entry for the view registry. */
export function mountAdminView( container ) {

	return new AdminView().mount( container );

}
