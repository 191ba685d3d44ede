// The lesson runner's forms for a teacher's classes: make a class (POST /classes; the server gives
// it a join code) and add a child to the chosen one (POST /children: a display name and an avatar
// of GET /children/avatars, nothing else about the child). Folded away under "New class or child"
// once the teacher has a class; the panel is told of what was made and shows it.

import { h } from '../shared/dom.js';

/** Longest display name a child may have (docs/lessons.md). */
const MAX_NAME = 40;

export class LessonRunnerRoster {

	/**
	 * @param {{ api: object, classId: () => number|null, onClass: ( made: object ) => any,
	 *   onChild: ( made: object ) => any }} options the API client, the chosen class, and what to
	 *   do with a class or child just made
	 */
	constructor( { api, classId, onClass, onChild } ) {

		this.api = api;
		this.classId = classId;
		this.onClass = onClass;
		this.onChild = onChild;
		this.className = h( 'input', { id: 'lr-new-class', className: 'lr-input', type: 'text', maxlength: '120', autocomplete: 'off', 'aria-label': 'Class name' } );
		this.childName = h( 'input', { id: 'lr-new-child', className: 'lr-input', type: 'text', maxlength: String( MAX_NAME ), autocomplete: 'off', 'aria-label': 'Child\'s name' } );
		this.avatar = h( 'select', { id: 'lr-avatar', className: 'lr-select', 'aria-label': 'Avatar' } );
		this.status = h( 'p', { className: 'lr-note', role: 'status', 'aria-live': 'polite' } );
		this.addChild = h( 'form', { className: 'lr-form', 'aria-label': 'Add a child', onSubmit: ( event ) => this.submit( event, () => this.makeChild() ) },
			h( 'label', { className: 'field-label', for: 'lr-new-child' }, 'Add a child to this class' ), this.childName,
			h( 'label', { className: 'lr-inline', for: 'lr-avatar' }, 'Picture', this.avatar ),
			h( 'button', { type: 'submit' }, 'Add child' ) );
		this.element = h( 'details', { className: 'lr-roster' },
			h( 'summary', {}, 'New class or child' ),
			h( 'form', { className: 'lr-form', 'aria-label': 'New class', onSubmit: ( event ) => this.submit( event, () => this.makeClass() ) },
				h( 'label', { className: 'field-label', for: 'lr-new-class' }, 'New class' ), this.className,
				h( 'button', { type: 'submit' }, 'Make class' ) ),
			this.addChild, this.status );

	}

	/** Fill the avatar chooser; open the forms when there is no class yet. */
	async load( hasClasses ) {

		if ( ! hasClasses ) this.element.open = true; // left as the teacher had it otherwise
		this.addChild.hidden = ! hasClasses;
		if ( this.avatar.options.length > 0 ) return;
		try {

			const avatars = await this.api.get( 'children/avatars' );
			this.avatar.replaceChildren( ...avatars.map( ( name ) => h( 'option', { value: name }, name ) ) );

		} catch ( error ) {

			this.status.textContent = `The pictures could not be loaded: ${ error.message }`;

		}

	}

	async submit( event, action ) {

		event.preventDefault();
		const buttons = this.element.querySelectorAll( 'button' );
		for ( const button of buttons ) button.disabled = true;
		try {

			await action();

		} catch ( error ) {

			this.status.textContent = error.message;

		} finally {

			for ( const button of buttons ) button.disabled = false;

		}

	}

	async makeClass() {

		const name = this.className.value.trim();
		if ( ! name ) return void ( this.status.textContent = 'Give the class a name.' );
		const made = await this.api.post( 'classes', { name } );
		this.className.value = '';
		this.status.textContent = `Made ${ made.name }: its code is ${ made.join_code }.`;
		this.addChild.hidden = false;
		await this.onClass( made );

	}

	async makeChild() {

		const classId = this.classId();
		const name = this.childName.value.trim();
		if ( classId === null ) return void ( this.status.textContent = 'Make a class first.' );
		if ( ! name ) return void ( this.status.textContent = 'Give the child a name (a first name or a nickname is enough).' );
		const made = await this.api.post( 'children', { class_id: classId, display_name: name, avatar: this.avatar.value } );
		this.childName.value = '';
		this.status.textContent = `Added ${ made.display_name }.`;
		await this.onChild( made );

	}

}
