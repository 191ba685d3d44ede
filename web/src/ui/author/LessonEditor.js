// The author's lesson editor (route `#/author`): the lessons, and one lesson's title, language,
// description and items (`#/author?lesson=ID`, `#/author?lesson=new`) with a live preview of the
// selected item on the head. Items are added, moved, changed and removed in a draft that only a
// save sends (PUT with If-Match, so that nobody's work is overwritten unseen). The server's 422
// is shown beside the fields it names; a stale save (412) keeps the draft and offers to reload
// the other version or to overwrite it; a lesson the author may not change (a starter lesson, or
// another author's) can be saved as a copy. Lessons import from and export to the JSON format of
// docs/lessons.md.

import { currentSession, onSessionChange } from '../../session.js';
import { h } from '../shared/dom.js';
import { saveAs } from '../shared/download.js';
import { LessonList } from './LessonEditorList.js';
import { createLessonClient } from './LessonEditorClient.js';
import { forgetDraft, keepDraft, keptDraft } from './LessonEditorDrafts.js';
import { ItemForm } from './LessonEditorForm.js';
import { editorLayout, itemRow } from './LessonEditorLayout.js';
import {
	MAX_ITEMS, authorHref, blankLesson, draftOf, fieldErrors, insertItem, isDirty, itemErrors,
	itemsWithErrors, lessonBody, moveItem, newItem, parseAuthorHash, removeItem, setField,
} from './LessonEditorModel.js';
import { LessonPreview } from './LessonEditorPreview.js';
import { phonemeInventory } from '../lessons/LessonRunnerViews.js';
import { signedOutPrompt, signInPrompt } from '../shared/SignInPrompt.js';
import { hasRole } from '../shared/signIn.js';
import { View } from '../shared/View.js';
import './lessonEditor.css';

/** Who writes lessons. */
export const AUTHOR_ROLES = Object.freeze( [ 'author', 'admin' ] );

export class LessonEditor extends View {

	/** @param {{ api?: object, client?: object, win?: Window }} options the lessons' client, made on `api` unless given */
	constructor( { api, client = null, win } = {} ) {

		super( { api, win } );
		this.client = client ?? createLessonClient( { api: this.api } );
		this.opened = 0;
		this.errors = new Map();

	}

	mount( container ) {

		this.attach( container, h( 'div', { className: 'lesson-editor' } ) );
		this.listen( this.window, 'hashchange', () => this.route() );
		this.listen( this.window, 'beforeunload', ( event ) => {

			if ( this.dirty ) event.preventDefault();

		} );
		this.onUnmount( onSessionChange( () => this.route( true ) ) );
		this.debugFields( { author: () => this.report() } );
		this.route();
		return this;

	}

	get dirty() {

		return Boolean( this.draft ) && ( this.lessonId === null || isDirty( this.draft, this.saved ) );

	}

	/** What window.glasshead.author reports. */
	report() {

		return {
			screen: this.screen ?? null, lesson: this.lessonId ?? null, title: this.draft?.title ?? null,
			items: this.draft?.items.map( ( item ) => item.target.text ) ?? [], selected: this.selected ?? null,
			dirty: this.dirty, etag: this.etag ?? null, saving: this.saving ?? false, conflict: Boolean( this.conflict ),
			errors: Object.fromEntries( this.errors ), message: this.message?.textContent ?? null,
			lessons: this.list?.lessons.map( ( l ) => l.id ) ?? [], preview: this.preview?.report() ?? null,
		};

	}

	/** Show what the address names. */
	async route( force = false ) {

		const { lesson } = parseAuthorHash( this.window.location.hash );
		const session = currentSession( { win: this.window } );
		if ( ! hasRole( session, AUTHOR_ROLES ) ) return this.showSignIn( session );
		if ( ! force && this.screen === 'editor' && lesson === ( this.lessonId ?? 'new' ) ) return;
		if ( lesson === null ) return this.showList();
		if ( lesson === 'new' ) return this.openDraft( null, blankLesson(), null );
		const opened = ++ this.opened;
		this.clear( 'loading' );
		this.root.append( h( 'p', { className: 'status le-loading', role: 'status' }, 'Opening the lesson…' ) );
		try {

			const { lesson: record, etag } = await this.client.get( lesson );
			if ( opened === this.opened ) this.openDraft( lesson, record, etag );

		} catch ( error ) {

			if ( opened === this.opened ) this.showError( error );

		}

	}

	clear( screen ) {

		this.screen = screen;
		this.preview?.dispose();
		this.preview = null;
		this.list = null;
		this.draft = null;
		this.conflict = null;
		this.errors = new Map();
		this.root.replaceChildren();

	}

	/** Who may write lessons is not signed in: a sign-in link (as someone else, for another role). */
	showSignIn( session ) {

		this.clear( 'sign-in' );
		const who = session?.kind === 'user' ? session.user : null;
		const said = who ? `The lesson editor is for authors and admins; you are signed in as ${ who.display_name || who.username } (${ who.role }).` : '';
		this.root.append( h( 'div', { className: 'le-page' }, h( 'h1', { className: 'title' }, 'Write lessons' ),
			said ? h( 'p', {}, said ) : '', signInPrompt( { reason: who ? 'as an author' : 'as an author to write lessons', win: this.window } ) ) );

	}

	showError( error ) {

		this.clear( 'error' );
		const prompt = signedOutPrompt( error, { win: this.window } );
		this.root.append( h( 'div', { className: 'le-page' }, prompt ?? h( 'p', { className: 'error', role: 'alert' }, error.message ),
			h( 'a', { className: 'le-link', href: authorHref() }, 'All lessons' ) ) );

	}

	showList() {

		this.clear( 'list' );
		this.list = new LessonList( {
			client: this.client, win: this.window,
			onImported: ( lesson ) => ( this.window.location.hash = authorHref( lesson.id ) ),
			onError: ( error ) => signedOutPrompt( error, { win: this.window } ),
		} );
		this.root.append( this.list.element );
		this.list.load();

	}

	/** Edit `record` (lesson `id`, or null for a new one) from its ETag `etag`. */
	openDraft( id, record, etag ) {

		this.clear( 'editor' );
		this.lessonId = id;
		this.etag = etag;
		this.saved = draftOf( record );
		this.draft = draftOf( record );
		this.selected = 0;
		this.build();
		const kept = keptDraft( this.window, id );
		if ( kept && isDirty( kept.draft, this.saved ) ) {

			// Changes not saved before (the page was closed, or the sign-in ran out): back in the
			// form, against the version they were made on, so that a save over a newer one is a 412.
			this.draft = kept.draft;
			this.etag = kept.etag ?? etag;
			this.say( 'Your changes not saved yet are back from before: save them, or reload to drop them.' );

		}

		this.render();
		this.preview.show( this.draft.items[ 0 ], { now: true } );

	}

	build() {

		Object.assign( this, editorLayout( {
			save: ( options ) => this.save( options ), exportLesson: () => this.exportLesson(), deleteLesson: () => this.deleteLesson(),
			reloadTheirs: () => this.reloadTheirs(), addItem: () => this.addItem(), changeMeta: ( key, value ) => this.changeMeta( key, value ),
		} ) );
		this.form = new ItemForm( { onChange: ( path, value ) => this.changeItem( path, value ) } );
		phonemeInventory( this.api ).then( ( inventory ) => {

			if ( ! this.form || ! this.draft ) return;
			this.form.inventory = inventory;
			this.render();

		} );
		this.preview = new LessonPreview();
		this.root.append( this.bar, this.lessonPane, h( 'section', { className: 'le-item' }, this.form.element ), this.preview.element );
		this.preview.start();

	}

	/** Write the draft, the selection and the messages into the page. */
	render() {

		const draft = this.draft;
		this.heading.textContent = this.lessonId === null ? 'New lesson' : `Lesson ${ this.lessonId }`;
		for ( const [ key, { control, error } ] of this.meta ) {

			if ( this.window.document.activeElement !== control ) control.value = draft[ key ];
			const message = this.errors.get( key ) ?? '';
			error.textContent = message;
			error.hidden = message === '';
			control.setAttribute( 'aria-invalid', String( message !== '' ) );

		}

		const general = [ this.errors.get( '' ), this.errors.get( 'items' ) ].filter( Boolean ).join( ' ' );
		this.generalError.textContent = general;
		this.generalError.hidden = general === '';
		const flagged = new Set( itemsWithErrors( this.errors ) );
		const rowActions = { select: ( k ) => this.select( k ), move: ( from, to ) => this.move( from, to ), remove: ( k ) => this.remove( k ) };
		this.itemList.replaceChildren( ...draft.items.map( ( item, k ) => itemRow( item, k, { selected: this.selected, count: draft.items.length, flagged: flagged.has( k ) }, rowActions ) ) );
		this.addButton.disabled = draft.items.length >= MAX_ITEMS;
		this.form.set( draft.items[ this.selected ], this.selected, itemErrors( this.errors, this.selected ) );
		const saved = this.lessonId !== null;
		this.copyButton.hidden = ! saved;
		this.exportButton.hidden = ! saved;
		this.deleteButton.hidden = ! saved;
		this.saveButton.disabled = Boolean( this.saving );
		this.conflictBox.hidden = ! this.conflict;
		this.root.classList.toggle( 'le-dirty', this.dirty );
		if ( this.dirty ) keepDraft( this.window, this.lessonId, this.draft, this.etag );
		else forgetDraft( this.window, this.lessonId );

	}

	select( k ) {

		this.selected = k;
		this.render();
		this.preview.show( this.draft.items[ k ], { now: true } );

	}

	changeMeta( key, value ) {

		this.draft[ key ] = value;
		this.errors.delete( key );
		this.render();

	}

	changeItem( path, value ) {

		const k = this.selected;
		this.draft.items[ k ] = setField( this.draft.items[ k ], path, value );
		this.errors.delete( `items.${ k }.${ path }` );
		if ( path.startsWith( 'target' ) ) this.errors.delete( `items.${ k }.target` );
		this.render();
		this.preview.show( this.draft.items[ k ] );

	}

	addItem() {

		const last = this.draft.items[ this.selected ];
		this.draft.items = insertItem( this.draft.items, this.selected + 1, newItem( last?.target.kind ?? 'word', '' ) );
		this.errors = new Map(); // item positions changed: the old messages no longer point right
		this.select( this.selected + 1 );

	}

	move( from, to ) {

		this.draft.items = moveItem( this.draft.items, from, to );
		this.errors = new Map();
		this.selected = this.selected === from ? Math.min( Math.max( to, 0 ), this.draft.items.length - 1 ) : this.selected;
		this.render();

	}

	remove( k ) {

		if ( this.draft.items.length <= 1 ) return;
		this.draft.items = removeItem( this.draft.items, k );
		this.errors = new Map();
		this.selected = Math.min( this.selected > k ? this.selected - 1 : this.selected, this.draft.items.length - 1 );
		this.select( this.selected );

	}

	say( text ) {

		this.message.textContent = text;

	}

	/** Save the draft: a new lesson, the lesson (If-Match), over a newer version, or a copy. */
	async save( { copy = false, overwrite = false } = {} ) {

		if ( this.saving ) return;
		const body = lessonBody( this.draft );
		this.saving = true;
		this.render();
		this.say( 'Saving…' );
		try {

			let result;
			if ( this.lessonId === null || copy ) result = await this.client.create( body );
			else result = await this.client.replace( this.lessonId, body, overwrite ? this.conflict?.etag ?? this.etag : this.etag );
			this.saving = false;
			this.afterSave( result, copy );

		} catch ( error ) {

			this.saving = false;
			this.saveFailed( error );

		}

	}

	afterSave( { lesson, etag }, copy ) {

		const created = this.lessonId !== lesson.id;
		if ( this.lessonId === null ) forgetDraft( this.window, null );
		this.lessonId = lesson.id;
		this.etag = etag;
		this.saved = draftOf( lesson );
		this.conflict = null;
		this.errors = new Map();
		this.render();
		const time = new Date().toLocaleTimeString( [], { hour: '2-digit', minute: '2-digit' } );
		this.say( copy ? `Saved as a new lesson, ${ lesson.id }, at ${ time }.` : `Saved at ${ time }.` );
		// The address names the lesson now; route() sees it is the one open and keeps the page.
		if ( created ) this.window.location.hash = authorHref( lesson.id );

	}

	saveFailed( error ) {

		if ( signedOutPrompt( error, { win: this.window } ) ) {

			this.say( 'You were signed out: sign in again and save; your changes are kept on this page until you leave it.' );

		} else if ( error.status === 412 ) {

			this.conflict = { etag: error.etag ?? null };
			this.say( '' );

		} else if ( error.status === 422 ) {

			this.errors = fieldErrors( error.detail );
			const flagged = itemsWithErrors( this.errors );
			if ( flagged.length && ! flagged.includes( this.selected ) ) this.selected = flagged[ 0 ];
			this.say( 'Not saved: see the messages beside the fields.' );

		} else if ( error.status === 403 ) {

			this.say( `Not saved: ${ typeof error.detail === 'string' ? error.detail : 'you may not change this lesson' }. Save it as a copy to make it yours.` );

		} else {

			this.say( `Not saved: ${ error.message }` );

		}

		this.render();

	}

	/** Drop the draft for the version someone else saved (asked first). */
	async reloadTheirs() {

		if ( ! this.window.confirm( 'Drop your changes and load the version someone else saved?' ) ) return;
		forgetDraft( this.window, this.lessonId );
		await this.route( true );

	}

	async exportLesson() {

		try {

			const { text, filename } = await this.client.exportFile( this.lessonId );
			saveAs( text, filename, 'application/json', this.window.document );
			this.say( this.dirty ? `Exported ${ filename }: the saved lesson, without the changes not saved yet.` : `Exported ${ filename }.` );

		} catch ( error ) {

			this.say( `Not exported: ${ error.message }` );

		}

	}

	async deleteLesson() {

		if ( ! this.window.confirm( `Delete the lesson "${ this.saved.title }" with its assignments and practice records?` ) ) return;
		try {

			await this.client.remove( this.lessonId, this.etag );
			this.window.location.hash = authorHref();

		} catch ( error ) {

			if ( error.status === 412 ) this.conflict = { etag: error.etag ?? null };
			else this.say( `Not deleted: ${ error.message }` );
			this.render();

		}

	}

	unmount() {

		this.clear( 'gone' );
		super.unmount();

	}

}

/** Route entry for the view registry. */
export function mountLessonEditor( container ) {

	return new LessonEditor().mount( container );

}
