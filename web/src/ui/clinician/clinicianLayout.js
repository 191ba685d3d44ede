// The clinician view's page, built once when it mounts: the choices and the legend at the side;
// the transport, the frame slider, the 3D target and the three palatograms (target, recording,
// agreement), the table of indices, the index curves and the strip of frames. `actions` are what
// the controls do; the view fills the elements in (ClinicianView.render). Long names are cut with
// an ellipsis by the stylesheet and shown whole on hover (their `title`).

import { AGREEMENT_EXPLANATION } from './clinicianText.js';
import { h } from '../shared/dom.js';
import { IndexPlot } from './IndexPlot.js';
import { PALATOGRAM_COLORS, Palatogram } from '../shared/Palatogram.js';
import { PalatogramStrip } from './PalatogramStrip.js';

/** Playback speeds offered, slowest first. */
export const SPEEDS = Object.freeze( [ 0.05, 0.1, 0.25, 0.5, 1 ] );
/**
 * The speed playback starts at: a tenth of real time, so that a take of 50 frames at 200 Hz
 * (0.25 s) plays in 2.5 s, slow enough to follow frame by frame.
 */
export const DEFAULT_SPEED = 0.1;

/** How a speed is offered. */
export function speedLabel( speed ) {

	return speed === 1 ? 'Real time' : `${ speed } x (${ Math.round( 1 / speed ) } times slower)`;

}

/**
 * @param {{ chooseTarget( name: string ), chooseRecording( id: string ), setSpeed( speed: number ),
 *   setFrame( frame: number ), step( delta: number ), lastFrame(), togglePlay() }} actions
 * @param {{ importBox?: HTMLElement }} parts made elsewhere: the import box (clinicianImport.js)
 * @returns {object} the elements and drawings the view fills in, `root` holding them all
 */
export function clinicianLayout( actions, { importBox = null } = {} ) {

	const ui = {};
	const option = ( value, label ) => h( 'option', { value }, label );
	ui.targetSelect = h( 'select', { 'aria-label': 'Target', onChange: () => actions.chooseTarget( ui.targetSelect.value ) }, option( '', 'No target' ) );
	ui.recordingSelect = h( 'select', { 'aria-label': 'Recording', onChange: () => actions.chooseRecording( ui.recordingSelect.value ) }, option( '', 'No recording' ) );
	ui.speedSelect = h( 'select', { 'aria-label': 'Playback speed', onChange: () => actions.setSpeed( Number( ui.speedSelect.value ) ) },
		...SPEEDS.map( ( s ) => option( String( s ), speedLabel( s ) ) ) );
	ui.speedSelect.value = String( DEFAULT_SPEED );
	ui.status = h( 'p', { className: 'status', role: 'status', 'aria-live': 'polite' }, 'Loading targets and recordings…' );
	ui.error = h( 'p', { className: 'error', role: 'alert', hidden: '' } );
	// Styled through the CSSOM: the page's Content-Security-Policy refuses style attributes.
	const swatch = ( color, outline ) => {

		const element = h( 'span', { className: 'cv-swatch' } );
		if ( outline ) element.style.border = `2px solid ${ color }`;
		else element.style.background = color;
		return element;

	};
	const legend = h( 'div', { className: 'cv-legend' },
		h( 'span', {}, swatch( PALATOGRAM_COLORS.contact ), 'contact (agreement: both)' ),
		h( 'span', {}, swatch( PALATOGRAM_COLORS.onlyRecording ), 'recording only' ),
		h( 'span', {}, swatch( PALATOGRAM_COLORS.onlyReference, true ), 'target only' ),
		h( 'span', {}, 'dot: no contact; front (R1) at the top' ) );
	const side = h( 'aside', { className: 'cv-side', 'aria-label': 'Choices' },
		h( 'h1', { className: 'cv-title' }, 'Clinician' ),
		h( 'label', {}, 'Target', ui.targetSelect ),
		h( 'label', {}, 'Recording', ui.recordingSelect ),
		h( 'label', {}, 'Playback', ui.speedSelect ),
		ui.status, ui.error, ...( importBox ? [ importBox ] : [] ), legend );

	const button = ( label, text, onClick ) => h( 'button', { type: 'button', 'aria-label': label, title: label, onClick }, text );
	ui.playButton = button( 'Play', 'Play', () => actions.togglePlay() );
	ui.slider = h( 'input', { type: 'range', className: 'cv-slider', min: '0', max: '0', value: '0', 'aria-label': 'Frame', onInput: () => actions.setFrame( Number( ui.slider.value ) ) } );
	ui.frameLabel = h( 'span', { className: 'cv-frame', 'aria-live': 'off' }, '' );
	const transport = h( 'div', { className: 'cv-transport', role: 'group', 'aria-label': 'Frames' },
		button( 'First frame', '|◀', () => actions.setFrame( 0 ) ),
		button( 'Previous frame', '◀', () => actions.step( - 1 ) ),
		ui.playButton,
		button( 'Next frame', '▶', () => actions.step( 1 ) ),
		button( 'Last frame', '▶|', () => actions.lastFrame() ),
		ui.frameLabel );

	const size = { width: 176, height: 196 };
	ui.targetPalatogram = new Palatogram( { ...size, ariaLabel: 'Target palatogram (synthetic)' } );
	ui.recordingPalatogram = new Palatogram( { ...size, ariaLabel: 'Recording palatogram (real)' } );
	ui.agreementPalatogram = new Palatogram( { ...size, ariaLabel: 'Agreement, electrode by electrode' } );
	ui.targetCaption = h( 'span', { className: 'cv-sub' }, 'none chosen' );
	ui.recordingCaption = h( 'span', { className: 'cv-sub' }, 'none chosen' );
	ui.agreementCaption = h( 'span', { className: 'cv-sub cv-figures' }, 'choose both' );
	ui.phoneScores = h( 'p', { className: 'cv-note cv-figures', hidden: '' } );
	const card = ( title, caption, palatogram, ...more ) => h( 'figure', { className: 'cv-card cv-narrow' }, h( 'figcaption', {}, title, caption ), palatogram.element, ...more );
	ui.table = h( 'table', { className: 'cv-table', 'aria-label': 'EPG indices of this frame' } );
	ui.stage3d = h( 'div', { className: 'cv-stage3d', role: 'img', 'aria-label': 'The target on the 3D palate: electrodes as dots, contacted ones as squares' } );
	ui.caption3d = h( 'figcaption', {}, 'Target on the palate' );
	const pair = h( 'div', { className: 'cv-pair' },
		h( 'figure', { className: 'cv-card cv-wide' }, ui.caption3d, ui.stage3d ),
		card( 'Target (synthetic)', ui.targetCaption, ui.targetPalatogram ),
		card( 'Recording (real)', ui.recordingCaption, ui.recordingPalatogram ),
		card( 'Agreement', ui.agreementCaption, ui.agreementPalatogram, ui.phoneScores, h( 'p', { className: 'cv-note' }, AGREEMENT_EXPLANATION ) ) );
	ui.plot = new IndexPlot( { width: 640, height: 270 } );
	ui.strip = new PalatogramStrip( { width: 760, height: 92, onSelect: ( i ) => actions.setFrame( i ) } );
	ui.stripCaption = h( 'figcaption', {}, 'Over time (click a frame)' );
	ui.plotCard = h( 'figure', { className: 'cv-card cv-grow' }, h( 'figcaption', {}, 'Indices over time: recording solid, target dashed' ), ui.plot.element );
	const curves = h( 'div', { className: 'cv-pair' },
		h( 'figure', { className: 'cv-card' }, h( 'figcaption', {}, 'Indices of this frame' ), ui.table ),
		ui.plotCard );
	ui.stripCard = h( 'figure', { className: 'cv-card' }, ui.stripCaption, ui.strip.element );
	ui.main = h( 'section', { className: 'cv-main', 'aria-label': 'Frames' }, transport, ui.slider, pair, curves, ui.stripCard );
	ui.root = h( 'div', { className: 'clinician', tabindex: '-1' }, side, ui.main );
	return ui;

}

/** Set the text of a caption that may be cut with an ellipsis, whole in its tooltip. */
export function setCaption( element, text ) {

	element.textContent = text;
	element.title = text;

}

/**
 * Fill the choosers with `choices` (ClinicianData.choices): the targets in their groups (a group
 * that could not be listed says why), the recordings by title; each option shows its whole label
 * on hover.
 */
export function fillChoices( ui, choices ) {

	const option = ( value, label ) => h( 'option', { value, title: label }, label );
	ui.targetSelect.replaceChildren( option( '', 'No target' ) );
	for ( const group of choices.groups ) {

		const options = group.targets.map( ( t ) => option( t.value, t.label ) );
		if ( group.error ) options.push( h( 'option', { value: '', disabled: true }, `unavailable: ${ group.error }` ) );
		ui.targetSelect.append( h( 'optgroup', { label: group.title }, ...options ) );

	}

	ui.recordingSelect.replaceChildren( option( '', 'No recording' ), ...choices.recordings.map( ( r ) => option( r.value, r.label ) ) );

}

/** Whether `select` offers `value`. */
export function offers( select, value ) {

	return [ ...select.options ].some( ( o ) => o.value === value && ! o.disabled );

}

/**
 * The view's keys, for a keydown listener: left and right arrows step, Home and End jump, space
 * plays and pauses (not while a choice or the slider has the focus, nor with a modifier).
 */
export function keyHandler( actions ) {

	const keys = {
		ArrowLeft: () => actions.step( - 1 ),
		ArrowRight: () => actions.step( 1 ),
		Home: () => actions.setFrame( 0 ),
		End: () => actions.lastFrame(),
		' ': () => actions.togglePlay(),
	};
	return ( event ) => {

		const tag = event.target?.tagName;
		if ( tag === 'SELECT' || tag === 'INPUT' || tag === 'TEXTAREA' || event.altKey || event.ctrlKey || event.metaKey ) return;
		const action = keys[ event.key ];
		if ( ! action ) return;
		event.preventDefault();
		action();

	};

}
