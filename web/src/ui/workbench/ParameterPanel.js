// Sliders for every articulation parameter, in the workbench's groups (jaw, lips, tongue
// sagittal, tongue coronal front, middle and back), bound to a ParamState: a slider sets its
// parameter; any change of the state (paste, reset, a saved pose) moves the sliders.

import { roundValue } from '../../core/paramState.js';
import { h } from '../shared/dom.js';

/** Group headings. */
const GROUP_TITLES = Object.freeze( {
	jaw: 'Jaw',
	lips: 'Lips',
	velum: 'Velum (soft palate)',
	'tongue sagittal': 'Tongue sagittal',
	'tongue coronal front': 'Tongue coronal: front',
	'tongue coronal middle': 'Tongue coronal: middle',
	'tongue coronal back': 'Tongue coronal: back',
} );

/** "front_groove_depth" -> "Front groove depth". */
export function humanise( name ) {

	const words = name.replace( /_/g, ' ' );
	return words.charAt( 0 ).toUpperCase() + words.slice( 1 );

}

/** The label shown inside a group: the group's own word is left out ("Groove depth" under "front"). */
export function shortLabel( name, group ) {

	const prefix = ( group ?? '' ).split( ' ' ).pop() + '_';
	return humanise( group?.startsWith( 'tongue coronal' ) && name.startsWith( prefix ) ? name.slice( prefix.length ) : name );

}

/** A slider step of about a 200th of the range, rounded down to 1, 2 or 5 times a power of ten. */
export function sliderStep( p ) {

	const raw = ( p.max - p.min ) / 200;
	if ( ! ( raw > 0 ) ) return 1;
	const power = 10 ** Math.floor( Math.log10( raw ) );
	const mantissa = raw / power;
	return ( mantissa >= 5 ? 5 : mantissa >= 2 ? 2 : 1 ) * power;

}

/** A value for display, one or two decimals: "2.5 mm", "2.25 mm", "12.0°", "−0.4 mm" (a true minus), "0.75" (a ratio). */
/**
 * One arrow press on a slider: about a 100th of the range, rounded up to 1, 2 or 5 times a power of
 * ten, so that the arrows cross any range in at most 100 presses (the slider's own step stays finer,
 * for dragging; PageUp and PageDown move a tenth of the range, as the browser does).
 */
export function keyStep( p ) {

	const raw = ( p.max - p.min ) / 100;
	if ( ! ( raw > 0 ) ) return 1;
	const power = 10 ** Math.floor( Math.log10( raw ) );
	const mantissa = raw / power;
	return ( mantissa <= 1 + 1e-9 ? 1 : mantissa <= 2 ? 2 : mantissa <= 5 ? 5 : 10 ) * power;

}

/** The value after an arrow key (`key`) on a slider of parameter `p` at `value`, or null for other keys. */
export function arrowValue( p, value, key ) {

	const direction = { ArrowRight: 1, ArrowUp: 1, ArrowLeft: - 1, ArrowDown: - 1 }[ key ];
	if ( ! direction ) return null;
	const step = keyStep( p );
	return Math.min( p.max, Math.max( p.min, roundValue( value + direction * step ) ) );

}

export function formatValue( value, unit ) {

	const text = roundValue( value ).toFixed( 2 ).replace( /(\.\d)0$/, '$1' );
	const signed = text === '-0.0' ? '0.0' : text.replace( /^-/, '\u2212' );
	if ( unit === 'deg' ) return `${ signed }°`;
	return unit && unit !== 'ratio' ? `${ signed } ${ unit }` : signed;

}

export class ParameterPanel {

	/** @param {import('../../core/paramState.js').ParamState} state */
	constructor( state ) {

		this.state = state;
		this.rows = new Map();
		const groups = state.groups().map( ( { group, parameters } ) => {

			const rows = parameters.map( ( p ) => this.row( p, group ) );
			return h( 'fieldset', { className: 'wb-group', 'data-group': group },
				h( 'legend', {}, GROUP_TITLES[ group ] ?? humanise( group ) ),
				...rows,
			);

		} );
		this.element = h( 'section', { className: 'wb-params', 'aria-label': 'Articulation parameters' }, ...groups );
		this.unsubscribe = state.onChange( ( names ) => this.sync( names ) );
		this.sync( null );

	}

	row( p, group ) {

		const id = `param-${ p.name }`;
		const slider = h( 'input', {
			type: 'range', id, min: String( p.min ), max: String( p.max ), step: String( sliderStep( p ) ),
			value: String( p.neutral ), 'aria-label': humanise( p.name ), 'data-param': p.name, className: 'wb-slider',
			onInput: () => this.state.set( p.name, Math.min( p.max, Math.max( p.min, Number( slider.value ) ) ) ),
			onKeydown: ( event ) => {

				const next = arrowValue( p, Number( slider.value ), event.key );
				if ( next === null || event.altKey || event.ctrlKey || event.metaKey ) return;
				event.preventDefault();
				slider.value = String( next );
				this.state.set( p.name, next );

			},
		} );
		const output = h( 'output', { for: id, className: 'wb-value' } );
		const row = h( 'div', { className: 'wb-row', title: p.description ?? '' },
			h( 'label', { for: id, className: 'wb-label' }, shortLabel( p.name, group ) ),
			slider,
			output,
		);
		this.rows.set( p.name, { slider, output, definition: p } );
		return row;

	}

	/** Show the state's values (names: the parameters that changed, or null for all). */
	sync( names ) {

		for ( const name of names ?? this.rows.keys() ) {

			const row = this.rows.get( name );
			if ( ! row ) continue;
			const value = this.state.get( name );
			// Leave a slider being dragged alone: its value is already the state's, to its step.
			if ( Math.abs( Number( row.slider.value ) - value ) > 1e-6 ) row.slider.value = String( roundValue( value ) );
			const text = formatValue( value, row.definition.unit );
			row.output.textContent = text;
			row.slider.setAttribute( 'aria-valuetext', text );

		}

	}

	setEnabled( enabled ) {

		for ( const { slider } of this.rows.values() ) slider.disabled = ! enabled;

	}

	dispose() {

		this.unsubscribe();
		this.element.remove();

	}

}
