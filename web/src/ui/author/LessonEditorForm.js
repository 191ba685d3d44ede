// The form of one lesson item in the author's editor: every field of the lesson format (the
// target, how a sound is said, the presentation, the audio with its cut-off or channels, the
// views with the camera, the zoom and the labels, the speed, what a spoken try is measured on),
// each
// with its label and a place beside it for the server's message about it (a 422 names the field).
// The form keeps its elements while the author types (focus stays put): `set( item, errors )`
// writes values and messages into them, and every change calls `onChange( path, value )` with the
// field's path in the item ('target.text', 'views.cutaway', 'speed').

import { h } from '../shared/dom.js';
import {
	AUDIO_KINDS, CAMERA_CHOICES, LABEL_CHOICES, LABEL_MODES, LISTEN_CHOICES, PRESENTATIONS, RANGES, SAID_AS_CHOICES, TARGET_KINDS, VIEW_SWITCHES,
	labelMode, labelsOfMode, listenChoice, listenFromChoice, readNumber, toggleLabel,
} from './LessonEditorModel.js';

let formCount = 0;

export class ItemForm {

	/** @param {{ onChange: ( path: string, value: any ) => void }} handlers */
	constructor( { onChange } ) {

		this.onChange = onChange;
		this.prefix = `le-item-${ ++ formCount }`;
		this.fields = new Map(); // path -> { control, error, row }
		this.heading = h( 'h2', { className: 'le-heading' }, 'Item' );
		this.itemError = h( 'p', { className: 'le-error', role: 'alert', hidden: '' } );
		this.element = h( 'form', { className: 'le-item-form', 'aria-label': 'Item', novalidate: '' },
			this.heading, this.itemError,
			this.select( 'target.kind', 'Target kind', TARGET_KINDS ),
			this.input( 'target.text', 'Target', { type: 'text', maxlength: '200', autocomplete: 'off', spellcheck: 'false' } ),
			this.howNote = h( 'p', { className: 'le-how', hidden: '' } ),
			this.select( 'presentation', 'Presentation', PRESENTATIONS ),
			this.select( 'said_as', 'A sound is said', SAID_AS_CHOICES, { show: ( value ) => value ?? '', read: ( value ) => value || null } ),
			this.select( 'audio.kind', 'Audio', AUDIO_KINDS ),
			this.input( 'audio.cutoff_hz', 'Low-pass cut-off, Hz', { type: 'number', min: String( RANGES.cutoff_hz[ 0 ] ), max: String( RANGES.cutoff_hz[ 1 ] ), step: '50', placeholder: 'the player’s' }, readNumber ),
			this.input( 'audio.channels', 'Vocoder channels', { type: 'number', min: String( RANGES.channels[ 0 ] ), max: String( RANGES.channels[ 1 ] ), step: '1', placeholder: 'the player’s' }, readNumber ),
			this.input( 'views.skin_transparency', 'Skin transparency (0 opaque, 1 invisible)', { type: 'number', min: '0', max: '1', step: '0.05' }, readNumber ),
			h( 'fieldset', { className: 'le-views' }, h( 'legend', {}, 'Views' ), ...VIEW_SWITCHES.map( ( view ) => this.checkbox( `views.${ view.key }`, view.label ) ) ),
			this.select( 'views.camera', 'Seen from', CAMERA_CHOICES ),
			this.input( 'views.zoom', `Zoom (1 mouth and throat, up to ${ RANGES.zoom[ 1 ] } on the mouth)`, { type: 'number', min: String( RANGES.zoom[ 0 ] ), max: String( RANGES.zoom[ 1 ] ), step: '0.25' }, readNumber ),
			this.labelPicker(),
			this.input( 'speed', 'Speed (1 natural, 0.1 ten times slower)', { type: 'number', min: String( RANGES.speed[ 0 ] ), max: String( RANGES.speed[ 1 ] ), step: '0.05' }, readNumber ),
			this.select( 'listen', 'A spoken try is measured on', LISTEN_CHOICES, { show: listenChoice, read: ( value ) => listenFromChoice( value, this.item?.listen ) } ),
		);
		this.element.addEventListener( 'submit', ( event ) => event.preventDefault() );
		/** The phoneme inventory (GET /phonemes by symbol), for how a sound is made; set by the editor. */
		this.inventory = new Map();

	}

	/** A labelled row: the control, then its message. */
	row( path, label, control, { inline = false } = {} ) {

		const id = `${ this.prefix }-${ path.replace( /\./g, '-' ) }`;
		control.id = id;
		const error = h( 'p', { className: 'le-error', id: `${ id }-error`, role: 'alert', hidden: '' } );
		const labelElement = h( 'label', { for: id }, label );
		const row = inline
			? h( 'div', { className: 'le-row le-check' }, control, labelElement, error )
			: h( 'div', { className: 'le-row' }, labelElement, control, error );
		this.fields.set( path, { control, error, row } );
		return row;

	}

	/** A select; `show` turns the item's value into an option's, `read` an option's back (the listen choice). */
	select( path, label, options, { show = null, read = ( value ) => value } = {} ) {

		const control = h( 'select', { className: 'le-control' }, ...options.map( ( option ) => h( 'option', { value: option.value }, option.label ) ) );
		control.addEventListener( 'change', () => this.onChange( path, read( control.value ) ) );
		if ( show ) this.shown = { ...this.shown, [ path ]: show };
		return this.row( path, label, control );

	}

	/** Which labels show: none, all, or a few chosen (a checkbox each, shown when choosing). */
	labelPicker() {

		const row = this.select( 'views.labels', 'Labels', LABEL_MODES, { show: labelMode, read: ( mode ) => labelsOfMode( mode, this.item?.views.labels ) } );
		this.labelBoxes = new Map( LABEL_CHOICES.map( ( { value, label } ) => {

			const box = h( 'input', { type: 'checkbox', className: 'le-checkbox', id: `${ this.prefix }-label-${ value }` } );
			box.addEventListener( 'change', () => this.onChange( 'views.labels', toggleLabel( this.item?.views.labels, value, box.checked ) ) );
			return [ value, { box, row: h( 'div', { className: 'le-check' }, box, h( 'label', { for: box.id }, label ) ) } ];

		} ) );
		this.labelChoices = h( 'fieldset', { className: 'le-views le-label-choices' }, h( 'legend', {}, 'The labels shown' ), ...[ ...this.labelBoxes.values() ].map( ( choice ) => choice.row ) );
		return h( 'div', {}, row, this.labelChoices );

	}

	input( path, label, attributes, read = ( value ) => value ) {

		const control = h( 'input', { className: 'le-control', ...attributes } );
		control.addEventListener( 'input', () => this.onChange( path, read( control.value ) ) );
		return this.row( path, label, control );

	}

	checkbox( path, label ) {

		const control = h( 'input', { type: 'checkbox', className: 'le-checkbox' } );
		control.addEventListener( 'change', () => this.onChange( path, control.checked ) );
		return this.row( path, label, control, { inline: true } );

	}

	/**
	 * Show `item` (number `index` from 0) and the messages about it: `errors` maps its fields'
	 * paths to messages ('' for the item as a whole; 'target' for the target as a whole).
	 */
	set( item, index, errors = new Map() ) {

		this.heading.textContent = `Item ${ index + 1 }`;
		this.item = item;
		for ( const [ path, { control, error, row } ] of this.fields ) {

			const stored = path.split( '.' ).reduce( ( v, key ) => v?.[ key ], item );
			const value = this.shown?.[ path ] ? this.shown[ path ]( stored ) : stored;
			if ( control.type === 'checkbox' ) control.checked = Boolean( value );
			else if ( control.ownerDocument.activeElement !== control || control.tagName === 'SELECT' ) control.value = value === null || value === undefined ? '' : String( value );
			// The target as a whole (an unknown phoneme) is said beside the target's text.
			const message = errors.get( path ) ?? ( path === 'target.text' ? errors.get( 'target' ) : undefined ) ?? '';
			error.textContent = message;
			error.hidden = message === '';
			control.setAttribute( 'aria-invalid', String( message !== '' ) );
			if ( message ) control.setAttribute( 'aria-describedby', error.id );
			else control.removeAttribute( 'aria-describedby' );
			if ( path === 'audio.cutoff_hz' ) row.hidden = item.audio.kind !== 'lowpass';
			if ( path === 'audio.channels' ) row.hidden = item.audio.kind !== 'vocoded';
			if ( path === 'said_as' ) row.hidden = item.target.kind !== 'phoneme';

		}

		const chosen = Array.isArray( item.views.labels ) ? new Set( item.views.labels ) : null;
		this.labelChoices.hidden = ! chosen;
		for ( const [ name, { box } ] of this.labelBoxes ) box.checked = Boolean( chosen?.has( name ) );

		const phoneme = item.target.kind === 'phoneme' ? this.inventory.get( item.target.text.trim() ) : null;
		this.howNote.textContent = phoneme?.how ? `How /${ phoneme.ipa }/ is made: ${ phoneme.how }` : '';
		this.howNote.hidden = ! phoneme?.how;

		const whole = errors.get( '' ) ?? '';
		this.itemError.textContent = whole;
		this.itemError.hidden = whole === '';

	}

}
