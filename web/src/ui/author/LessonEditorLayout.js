// The author's editor page, built once per lesson opened (LessonEditor.js fills it in): the bar
// of actions with the message and the 412 box, the lesson's title, language and description with
// a place for the server's message under each, and the list of items, each with buttons to choose,
// move and remove it. `actions` are what the controls do.

import { h } from '../shared/dom.js';
import { CONFLICT_MESSAGE, authorHref, itemSummary } from './LessonEditorModel.js';

const META_FIELDS = Object.freeze( [
	Object.freeze( { key: 'title', label: 'Title', attributes: { type: 'text', maxlength: '200' } } ),
	Object.freeze( { key: 'language', label: 'Language (e.g. en-US)', attributes: { type: 'text', maxlength: '35', spellcheck: 'false' } } ),
	Object.freeze( { key: 'description', label: 'Description', tag: 'textarea', attributes: { rows: '2', maxlength: '2000' } } ),
] );

/**
 * @param {{ save: Function, exportLesson: Function, deleteLesson: Function, reloadTheirs: Function,
 *   addItem: Function, changeMeta: ( key: string, value: string ) => void }} actions
 * @returns {object} the elements the editor fills in: `bar` and `lessonPane` hold the rest
 */
export function editorLayout( actions ) {

	const ui = {};
	const button = ( label, onClick, className = '' ) => h( 'button', { type: 'button', className, onClick }, label );
	ui.saveButton = button( 'Save', () => actions.save(), 'le-save' );
	ui.copyButton = button( 'Save as a copy', () => actions.save( { copy: true } ) );
	ui.exportButton = button( 'Export JSON', () => actions.exportLesson() );
	ui.deleteButton = button( 'Delete lesson', () => actions.deleteLesson(), 'le-danger' );
	ui.message = h( 'p', { className: 'status le-message', role: 'status', 'aria-live': 'polite' } );
	ui.conflictBox = h( 'div', { className: 'le-conflict', role: 'alert', hidden: '' },
		h( 'p', {}, CONFLICT_MESSAGE ),
		button( 'Reload their version', () => actions.reloadTheirs() ),
		button( 'Overwrite with mine', () => actions.save( { overwrite: true } ), 'le-danger' ) );
	ui.heading = h( 'h1', { className: 'title le-title' } );
	ui.bar = h( 'div', { className: 'le-bar' },
		h( 'a', { className: 'le-link', href: authorHref() }, 'All lessons' ), ui.heading,
		ui.saveButton, ui.copyButton, ui.exportButton, ui.deleteButton, ui.message, ui.conflictBox );

	ui.meta = new Map( META_FIELDS.map( ( field ) => {

		const control = h( field.tag ?? 'input', { className: 'le-control', id: `le-${ field.key }`, ...field.attributes } );
		control.addEventListener( 'input', () => actions.changeMeta( field.key, control.value ) );
		const error = h( 'p', { className: 'le-error', id: `le-${ field.key }-error`, role: 'alert', hidden: '' } );
		return [ field.key, { control, error, row: h( 'div', { className: 'le-row' }, h( 'label', { for: control.id }, field.label ), control, error ) } ];

	} ) );
	ui.itemList = h( 'ol', { className: 'le-items', 'aria-label': 'Items' } );
	ui.addButton = button( 'Add an item', () => actions.addItem(), 'le-add' );
	ui.generalError = h( 'p', { className: 'le-error', role: 'alert', hidden: '' } );
	ui.lessonPane = h( 'section', { className: 'le-lesson', 'aria-label': 'Lesson' },
		ui.generalError, ...[ ...ui.meta.values() ].map( ( field ) => field.row ),
		h( 'h2', { className: 'le-heading' }, 'Items' ), ui.itemList, ui.addButton );
	return ui;

}

/**
 * The list's row of item `k`: a button that chooses it (its number and summary, and a flag when
 * the server had something to say about it), and buttons to move it up, down and remove it.
 * @param {{ selected: number, count: number, flagged: boolean }} state
 * @param {{ select( k ), move( from, to ), remove( k ) }} actions
 */
export function itemRow( item, k, { selected, count, flagged }, actions ) {

	const small = ( label, name, onClick, disabled ) => h( 'button', {
		type: 'button', className: 'le-small', 'aria-label': `${ name } item ${ k + 1 }`, title: `${ name } item ${ k + 1 }`, onClick, ...( disabled ? { disabled: '' } : {} ),
	}, label );
	const choose = h( 'button', {
		type: 'button', className: 'le-choose', 'aria-current': String( k === selected ), onClick: () => actions.select( k ),
	}, h( 'span', { className: 'le-number' }, `${ k + 1 }` ), ` ${ itemSummary( item ) }`, flagged ? h( 'span', { className: 'le-flag' }, ' (see the message)' ) : '' );
	return h( 'li', { className: flagged ? 'le-flagged' : '' }, choose,
		small( '↑', 'Move up', () => actions.move( k, k - 1 ), k === 0 ),
		small( '↓', 'Move down', () => actions.move( k, k + 1 ), k === count - 1 ),
		small( '✕', 'Remove', () => actions.remove( k ), count === 1 ) );

}
