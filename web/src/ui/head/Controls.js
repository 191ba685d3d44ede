// The head view's control panel: skin transparency, cutaway, views, loading status and errors.
// Big targets for tablets and projectors; every control has an accessible name.

import { VIEW_NAMES } from '../../scene/viewPresets.js';
import { h } from '../shared/dom.js';

const VIEW_LABELS = Object.freeze( { front: 'Front', profile: 'Profile', 'three-quarter': 'Three-quarter' } );

export class Controls {

	/**
	 * handlers: { onTransparency( percent ), onCutaway( on ), onLabels( on ), onView( name ) }.
	 * initial: { transparency, cutaway, labels, view }.
	 */
	constructor( handlers, initial ) {

		this.handlers = handlers;

		this.slider = h( 'input', {
			type: 'range', min: '0', max: '100', step: '1', value: String( initial.transparency ),
			id: 'skin-transparency', 'aria-label': 'Skin transparency', className: 'slider',
			onInput: () => this.transparencyChanged(),
		} );
		this.sliderValue = h( 'output', { for: 'skin-transparency', className: 'slider-value' } );

		this.cutawayButton = h( 'button', {
			type: 'button', className: 'toggle', 'aria-pressed': String( initial.cutaway ),
			onClick: () => this.setCutaway( this.cutawayButton.getAttribute( 'aria-pressed' ) !== 'true', true ),
		}, 'Cutaway' );

		this.labelsButton = h( 'button', {
			type: 'button', className: 'toggle', 'aria-pressed': String( Boolean( initial.labels ) ),
			onClick: () => this.setLabels( this.labelsButton.getAttribute( 'aria-pressed' ) !== 'true', true ),
		}, 'Labels' );

		this.viewButtons = new Map( VIEW_NAMES.map( ( name ) => [ name, h( 'button', {
			type: 'button', className: 'view-button', 'aria-pressed': String( name === initial.view ),
			'data-view': name, onClick: () => this.setView( name, true ),
		}, VIEW_LABELS[ name ] ) ] ) );

		this.status = h( 'p', { className: 'status', role: 'status', 'aria-live': 'polite' } );
		this.progress = h( 'progress', { className: 'progress', max: '1', 'aria-label': 'Loading the anatomy', hidden: '' } );
		this.error = h( 'p', { className: 'error', role: 'alert', hidden: '' } );

		this.element = h( 'aside', { className: 'panel', 'aria-label': 'Head controls' },
			h( 'h1', { className: 'title' }, 'Glasshead' ),
			h( 'div', { className: 'field' },
				h( 'label', { for: 'skin-transparency', className: 'field-label' }, 'Skin transparency' ),
				h( 'div', { className: 'slider-row' }, this.slider, this.sliderValue ),
			),
			h( 'div', { className: 'field' }, this.cutawayButton ),
			h( 'div', { className: 'field' }, this.labelsButton ),
			h( 'div', { className: 'field' },
				h( 'span', { className: 'field-label', id: 'view-label' }, 'View' ),
				h( 'div', { className: 'view-buttons', role: 'group', 'aria-labelledby': 'view-label' }, ...this.viewButtons.values() ),
			),
			this.progress,
			this.status,
			this.error,
		);

		this.showTransparency( initial.transparency );

	}

	transparencyChanged() {

		const percent = Number( this.slider.value );
		this.showTransparency( percent );
		this.handlers.onTransparency( percent );

	}

	showTransparency( percent ) {

		this.sliderValue.textContent = `${ percent } %`;
		this.slider.setAttribute( 'aria-valuetext', `${ percent } percent` );

	}

	setCutaway( on, fromUser = false ) {

		this.cutawayButton.setAttribute( 'aria-pressed', String( on ) );
		if ( fromUser ) this.handlers.onCutaway( on );

	}

	setLabels( on, fromUser = false ) {

		this.labelsButton.setAttribute( 'aria-pressed', String( on ) );
		if ( fromUser ) this.handlers.onLabels?.( on );

	}

	setView( name, fromUser = false ) {

		for ( const [ view, button ] of this.viewButtons ) button.setAttribute( 'aria-pressed', String( view === name ) );
		if ( fromUser ) this.handlers.onView( name );

	}

	/** Enable or disable the controls (disabled while loading or after a failure). */
	setEnabled( enabled ) {

		for ( const control of [ this.slider, this.cutawayButton, this.labelsButton, ...this.viewButtons.values() ] ) control.disabled = ! enabled;

	}

	showStatus( text ) {

		this.status.textContent = text;

	}

	/** Show loading progress (done of total files); null hides the bar. */
	showProgress( done, total ) {

		if ( done === null ) {

			this.progress.hidden = true;
			return;

		}

		this.progress.hidden = false;
		if ( total > 0 ) this.progress.value = done / total;
		else this.progress.removeAttribute( 'value' ); // indeterminate until the list of meshes arrives

	}

	showError( text ) {

		this.error.textContent = text;
		this.error.hidden = ! text;

	}

}
