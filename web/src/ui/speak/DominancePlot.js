// The dominance curves of one chosen parameter over time (Cohen and Massaro 1993): for each phone
// of the utterance its dominance D(t) = alpha * exp( -theta * |t - centre|^c ), one curve per phone,
// under the parameter's track (the dominance-weighted average of the targets), with the current
// time as a line. Dominance is per group of parameters (tongue tip, tongue body, jaw, lip rounding,
// lip closure, velum): the answer of POST /utterances with `dominance: true` gives the curves per
// group and each parameter's group. Drawing goes through the injected 2D context.

import { h } from '../shared/dom.js';

/** Colours of the phones' curves, in turn; the track, the playhead and the phone boundaries. */
export const DOMINANCE_COLORS = Object.freeze( {
	curves: [ '#1f6feb', '#b4384a', '#2da44e', '#bf8700', '#8250df', '#0a7f8f' ],
	track: '#1f2328', playhead: '#d1242f', boundary: '#d0d7de', background: '#ffffff', text: '#57606a',
} );
/** The parameter shown first when the utterance has it. */
const FIRST_PARAMETER = 'tip_height';
const MARGIN = Object.freeze( { left: 6, right: 6, top: 8, bottom: 16 } );

export class DominancePlot {

	/**
	 * @param {{ element: HTMLCanvasElement, ctx: CanvasRenderingContext2D, width: number,
	 *   height: number }} canvas where to draw (CSS pixels)
	 * @param {{ names: string[], definition: ( name: string ) => object }} state the parameters
	 */
	constructor( canvas, state ) {

		this.canvas = canvas;
		this.state = state;
		this.utterance = null;
		this.parameter = null;
		this.time = 0;
		this.draws = 0;
		this.select = h( 'select', { className: 'sp-select', 'aria-label': 'Parameter', onChange: () => this.choose( this.select.value ) } );
		this.note = h( 'p', { className: 'sp-note' } );
		this.legend = 'Thin: each phoneme\'s dominance. Thick: the parameter.';
		this.element = h( 'div', { className: 'sp-dominance' }, this.select, canvas.element, this.note );

	}

	/** A new utterance: its parameters with dominance curves go into the chooser. */
	set( utterance ) {

		this.utterance = utterance;
		const groups = utterance?.dominance?.parameters ?? {};
		const names = this.state.names.filter( ( name ) => name in groups && utterance.tracks?.[ name ] );
		this.select.replaceChildren( ...names.map( ( name ) => h( 'option', { value: name }, `${ label( name ) } (${ groups[ name ].replace( /_/g, ' ' ) })` ) ) );
		this.select.disabled = names.length === 0;
		this.note.textContent = names.length ? this.legend : 'This answer has no dominance curves.';
		const keep = names.includes( this.parameter ) ? this.parameter : names.includes( FIRST_PARAMETER ) ? FIRST_PARAMETER : names[ 0 ] ?? null;
		this.choose( keep );

	}

	choose( name ) {

		this.parameter = name;
		if ( name ) this.select.value = name;
		this.draw();

	}

	/** Move the playhead to `t` seconds. */
	show( t ) {

		if ( t === this.time ) return;
		this.time = t;
		this.draw();

	}

	draw() {

		const { ctx, width, height } = this.canvas;
		drawDominance( ctx, { utterance: this.utterance, parameter: this.parameter, time: this.time, range: this.parameter ? this.state.definition( this.parameter ) : null }, { width, height } );
		this.draws ++;

	}

	/** What window.glasshead.speech.dominance reports. */
	report() {

		const group = this.parameter ? this.utterance?.dominance?.parameters?.[ this.parameter ] ?? null : null;
		return { parameter: this.parameter, group, curves: group ? this.utterance.dominance.groups[ group ].length : 0, draws: this.draws };

	}

}

function label( name ) {

	return name.replace( /_/g, ' ' );

}

/**
 * Draw the dominance curves of `parameter` (one per phone, scaled to the largest), the phone
 * boundaries and symbols, the parameter's track scaled to its range, and a line at `time`.
 * @param {CanvasRenderingContext2D} ctx
 * @param {{ utterance: object|null, parameter: string|null, time: number, range: { min: number, max: number }|null }} scene
 */
export function drawDominance( ctx, { utterance, parameter, time, range }, { width, height } ) {

	ctx.save();
	ctx.fillStyle = DOMINANCE_COLORS.background;
	ctx.fillRect( 0, 0, width, height );
	const group = parameter ? utterance?.dominance?.parameters?.[ parameter ] : null;
	const curves = group ? utterance.dominance.groups[ group ] : null;
	if ( ! curves ) {

		ctx.restore();
		return;

	}

	const duration = utterance.duration_s;
	const rate = utterance.rate_hz;
	const plotW = width - MARGIN.left - MARGIN.right;
	const plotH = height - MARGIN.top - MARGIN.bottom;
	const x = ( t ) => MARGIN.left + plotW * t / duration;
	const y = ( v ) => MARGIN.top + plotH * ( 1 - v );

	ctx.font = '12px system-ui, sans-serif';
	ctx.textAlign = 'center';
	ctx.textBaseline = 'top';
	for ( const phone of utterance.phones ) {

		ctx.strokeStyle = DOMINANCE_COLORS.boundary;
		ctx.lineWidth = 1;
		ctx.beginPath();
		ctx.moveTo( x( phone.start_s ), MARGIN.top );
		ctx.lineTo( x( phone.start_s ), height - MARGIN.bottom );
		ctx.stroke();
		if ( phone.symbol !== 'sil' ) {

			ctx.fillStyle = DOMINANCE_COLORS.text;
			ctx.fillText( phone.ipa ?? phone.symbol, x( ( phone.start_s + phone.end_s ) / 2 ), height - MARGIN.bottom + 2 );

		}

	}

	let peak = 0;
	for ( const curve of curves ) for ( const v of curve ) if ( v > peak ) peak = v;
	curves.forEach( ( curve, k ) => {

		ctx.strokeStyle = DOMINANCE_COLORS.curves[ k % DOMINANCE_COLORS.curves.length ];
		ctx.lineWidth = 1.5;
		ctx.beginPath();
		curve.forEach( ( v, i ) => ( i ? ctx.lineTo( x( i / rate ), y( v / peak ) ) : ctx.moveTo( x( 0 ), y( v / peak ) ) ) );
		ctx.stroke();

	} );

	const track = utterance.tracks[ parameter ];
	if ( track && range && range.max > range.min ) {

		ctx.strokeStyle = DOMINANCE_COLORS.track;
		ctx.lineWidth = 3;
		ctx.beginPath();
		track.forEach( ( v, i ) => {

			const yy = y( ( v - range.min ) / ( range.max - range.min ) );
			if ( i ) ctx.lineTo( x( i / rate ), yy );
			else ctx.moveTo( x( 0 ), yy );

		} );
		ctx.stroke();

	}

	ctx.strokeStyle = DOMINANCE_COLORS.playhead;
	ctx.lineWidth = 2;
	ctx.beginPath();
	ctx.moveTo( x( time ), MARGIN.top );
	ctx.lineTo( x( time ), height - MARGIN.bottom );
	ctx.stroke();
	ctx.restore();

}
