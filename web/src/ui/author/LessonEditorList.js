// The author's list of lessons (`#/author`): every lesson with a link to edit it, a new lesson,
// and an import of a lesson file (the JSON an export gives, docs/lessons.md), checked on the page
// for being JSON at all and by the server for the rest (its 422 is shown as it says it).

import { h } from '../shared/dom.js';
import { authorHref, parseLessonFile } from './LessonEditorModel.js';

export class LessonList {

	/**
	 * @param {{ client: object, win?: Window, onImported: Function, onError: Function }} options
	 *   `onImported( lesson )` after an import; `onError( error )` returns an element to show
	 *   instead of the message (a sign-in prompt for a 401), or null
	 */
	constructor( { client, win = globalThis.window, onImported, onError } ) {

		this.client = client;
		this.window = win;
		this.onImported = onImported;
		this.onError = onError;
		this.lessons = [];
		this.status = h( 'p', { className: 'status', role: 'status', 'aria-live': 'polite' }, 'Loading the lessons…' );
		this.list = h( 'ul', { className: 'le-lessons', 'aria-label': 'Lessons' } );
		this.file = h( 'input', { type: 'file', accept: '.json,application/json', id: 'le-import-file', className: 'le-file' } );
		this.file.addEventListener( 'change', () => this.importChosen() );
		this.element = h( 'div', { className: 'le-page' },
			h( 'h1', { className: 'title' }, 'Write lessons' ),
			h( 'div', { className: 'le-actions' },
				h( 'a', { className: 'le-link le-primary', href: authorHref( 'new' ) }, 'New lesson' ),
				h( 'label', { className: 'le-link', for: this.file.id }, 'Import a lesson file (JSON)' ), this.file ),
			this.status, this.list );

	}

	async load() {

		try {

			this.lessons = await this.client.list();

		} catch ( error ) {

			this.fail( error );
			return;

		}

		this.list.replaceChildren( ...this.lessons.map( ( lesson ) => h( 'li', {},
			h( 'a', { className: 'le-lesson-link', href: authorHref( lesson.id ) }, lesson.title ),
			h( 'span', { className: 'le-note' }, ` ${ lesson.n_items } item${ lesson.n_items === 1 ? '' : 's' }, ${ lesson.language }` ) ) ) );
		this.status.textContent = this.lessons.length ? '' : 'No lessons yet: make a new one or import a file.';

	}

	fail( error ) {

		const replacement = this.onError( error );
		if ( replacement ) this.status.replaceChildren( replacement );
		else this.status.textContent = error.message;

	}

	async importChosen() {

		const file = this.file.files?.[ 0 ];
		if ( ! file ) return;
		this.status.textContent = `Importing ${ file.name }…`;
		try {

			const content = parseLessonFile( await file.text() );
			const { lesson } = await this.client.importLesson( content );
			this.status.textContent = `Imported "${ lesson.title }".`;
			this.onImported( lesson );

		} catch ( error ) {

			const said = typeof error.detail === 'string' ? error.detail : error.message;
			const prompt = this.onError( error );
			if ( prompt ) this.status.replaceChildren( prompt );
			else this.status.textContent = `${ file.name } was not imported: ${ said }`;

		} finally {

			this.file.value = '';

		}

	}

}
