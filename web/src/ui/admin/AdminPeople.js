// The people who sign in, on the admin's page: every teacher, clinician, author and admin
// (GET /users), a form to add one (POST /users: a name, a username, a role and a first password,
// which the page can make up and show once), and for each a rename and a removal after a
// confirmation. Each change reads the user's ETag first and writes with If-Match, so a change
// someone else made meanwhile is a 412 said in words, never overwritten. The server keeps the
// last admin (409), and the page says so.

import { ApiError } from '../../api.js';
import { h } from '../shared/dom.js';

/** The roles an admin gives, in the order the form offers them. */
export const STAFF_ROLES = Object.freeze( [ 'teacher', 'clinician', 'author', 'admin' ] );
/** Letters of a made-up password: no look-alikes (0/o, 1/l/i), easy to read out and type. */
const PASSWORD_LETTERS = 'abcdefghjkmnpqrstuvwxyz23456789';
/** Length of a made-up password: about 59 bits from 31 letters. */
const PASSWORD_LENGTH = 12;

/** A password to give a new person, in groups of four ('k7pq-3mdx-vw9a'). */
export function madePassword( random = ( n ) => crypto.getRandomValues( new Uint32Array( n ) ) ) {

	const values = random( PASSWORD_LENGTH );
	const letters = Array.from( values, ( v ) => PASSWORD_LETTERS[ v % PASSWORD_LETTERS.length ] );
	return letters.join( '' ).replace( /(.{4})(?=.)/g, '$1-' );

}

/** What a refused change says, in plain words. */
export function peopleErrorWords( error ) {

	if ( error?.status === 412 ) return 'Someone else changed this person meanwhile: the list is read again, so look and try once more.';
	if ( error?.status === 409 ) return String( error.detail ?? error.message ).replace( /^field username: /, 'That username: ' );
	if ( error?.status === 422 ) return String( error.detail ?? error.message ).replace( /^body\.|^field /, '' );
	return error?.message ?? String( error );

}

export class AdminPeople {

	/** @param {{ api: object, me: () => number|null }} options the page's client; who is signed in */
	constructor( { api, me } ) {

		this.api = api;
		this.me = me;
		this.state = { users: [], added: [], renamed: [], removed: [], message: '' };
		this.message = h( 'p', { className: 'status', role: 'status', 'aria-live': 'polite' } );
		this.list = h( 'ul', { className: 'admin-people', 'aria-label': 'People who sign in' } );
		this.element = h( 'section', { className: 'admin-section', 'aria-labelledby': 'admin-people-title' },
			h( 'h2', { id: 'admin-people-title' }, 'People who sign in' ), this.addForm(), this.message, this.list );

	}

	say( text ) {

		this.state.message = text;
		this.message.textContent = text;

	}

	addForm() {

		const field = ( id, label, attributes ) => {

			const input = h( 'input', { id, className: 'admin-input', ...attributes } );
			return [ input, h( 'div', { className: 'admin-field' }, h( 'label', { for: id }, label ), input ) ];

		};

		const [ name, nameRow ] = field( 'admin-new-name', 'Name shown', { type: 'text', maxlength: '120', autocomplete: 'off', required: '' } );
		const [ username, usernameRow ] = field( 'admin-new-username', 'Username (an email address is fine)', { type: 'text', maxlength: '120', autocomplete: 'off', autocapitalize: 'none', spellcheck: 'false', required: '' } );
		const [ password, passwordRow ] = field( 'admin-new-password', 'First password (8 characters or more)', { type: 'text', autocomplete: 'new-password', spellcheck: 'false', minlength: '8', required: '' } );
		const role = h( 'select', { id: 'admin-new-role', className: 'admin-input' }, ...STAFF_ROLES.map( ( r ) => h( 'option', { value: r }, r ) ) );
		const make = h( 'button', { type: 'button', onClick: () => {

			password.value = madePassword();

		} }, 'Make one up' );
		this.fields = { name, username, password, role };
		return h( 'form', { className: 'admin-add', 'aria-label': 'Add a person', novalidate: '', onSubmit: ( event ) => {

			event.preventDefault();
			this.add();

		} }, nameRow, usernameRow, h( 'div', { className: 'admin-field' }, h( 'label', { for: 'admin-new-role' }, 'Role' ), role ),
		h( 'div', { className: 'admin-password' }, passwordRow, make ), h( 'button', { type: 'submit', className: 'admin-primary' }, 'Add this person' ) );

	}

	async load() {

		try {

			const { users } = await this.api.get( 'users?limit=1000' );
			this.state.users = users.map( ( u ) => u.id );
			this.list.replaceChildren( ...users.map( ( user ) => this.row( user ) ) );

		} catch ( error ) {

			this.say( `The people could not be loaded: ${ peopleErrorWords( error ) }` );

		}

	}

	async add() {

		const { name, username, password, role } = this.fields;
		if ( ! name.value.trim() || ! username.value.trim() ) return this.say( 'Give the person a name and a username.' );
		if ( password.value.length < 8 ) return this.say( 'A password has 8 characters or more: type one, or Make one up.' );
		try {

			const user = await this.api.post( 'users', { display_name: name.value.trim(), username: username.value.trim(), role: role.value, password: password.value } );
			this.state.added.push( user.id );
			this.say( `Added ${ user.display_name } (${ user.role }). Give them the username ${ user.username } and the password ${ password.value }; they can sign in now.` );
			for ( const input of [ name, username, password ] ) input.value = '';
			await this.load();

		} catch ( error ) {

			this.say( `Not added: ${ peopleErrorWords( error ) }` );

		}

	}

	row( user ) {

		const box = h( 'div', { className: 'admin-confirm', hidden: '' } );
		const you = user.id === this.me();
		return h( 'li', { className: 'admin-person', 'data-user': String( user.id ) },
			h( 'span', { className: 'admin-name' }, `${ user.display_name } `, h( 'span', { className: 'admin-who' }, `${ user.username }, ${ user.role }${ you ? ' (you)' : '' }` ) ),
			h( 'button', { type: 'button', 'aria-label': `Rename ${ user.display_name }…`, onClick: () => this.askRename( user, box ) }, 'Rename…' ),
			you ? '' : h( 'button', { type: 'button', className: 'admin-danger', 'aria-label': `Remove ${ user.display_name }…`, onClick: () => this.askRemove( user, box ) }, 'Remove…' ),
			box );

	}

	/** The user's ETag, read now: a write goes ahead only while the user is still as read. */
	async etagOf( user ) {

		return ( await this.api.exchange( 'GET', `users/${ user.id }` ) ).headers?.get( 'ETag' ) ?? null;

	}

	askRename( user, box ) {

		const input = h( 'input', { type: 'text', className: 'admin-input', value: user.display_name, maxlength: '120', 'aria-label': `New name for ${ user.display_name }` } );
		const form = h( 'form', { className: 'admin-rename', onSubmit: async ( event ) => {

			event.preventDefault();
			await this.rename( user, input.value.trim(), box );

		} }, input, h( 'button', { type: 'submit', className: 'admin-primary' }, 'Save the name' ), this.cancel( box ) );
		box.replaceChildren( form );
		box.hidden = false;
		input.select();

	}

	async rename( user, name, box ) {

		if ( ! name ) return this.say( 'A name cannot be empty.' );
		try {

			const changed = await this.api.exchange( 'PATCH', `users/${ user.id }`, { body: { display_name: name }, headers: { 'If-Match': await this.etagOf( user ) } } );
			this.state.renamed.push( user.id );
			box.hidden = true;
			this.say( `${ user.display_name } is now ${ changed.body.display_name }.` );
			await this.load();

		} catch ( error ) {

			this.say( `Not renamed: ${ peopleErrorWords( error ) }` );
			if ( error instanceof ApiError && error.status === 412 ) await this.load();

		}

	}

	askRemove( user, box ) {

		box.replaceChildren( h( 'p', {}, `${ user.display_name } will no longer sign in. What they made (lessons, classes) stays, and admins keep it.` ),
			h( 'button', { type: 'button', className: 'admin-danger admin-really', onClick: () => this.remove( user, box ) }, `Remove ${ user.display_name }` ), this.cancel( box ) );
		box.hidden = false;
		box.querySelector( '.admin-cancel' ).focus();

	}

	async remove( user, box ) {

		try {

			await this.api.exchange( 'DELETE', `users/${ user.id }`, { headers: { 'If-Match': await this.etagOf( user ) }, read: 'text' } );
			this.state.removed.push( user.id );
			box.closest( 'li' )?.remove();
			this.state.users = this.state.users.filter( ( id ) => id !== user.id );
			this.say( `Removed ${ user.display_name }.` );

		} catch ( error ) {

			this.say( `Not removed: ${ peopleErrorWords( error ) }` );

		}

	}

	cancel( box ) {

		return h( 'button', { type: 'button', className: 'admin-cancel', onClick: () => {

			box.hidden = true;

		} }, 'Cancel' );

	}

}
