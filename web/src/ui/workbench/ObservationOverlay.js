// The workbench's "Observation" group: a measured tongue shape (GET /observations, VocalTractLab's
// JD3 shapes in the project frame) on the tongue with its error vectors, before and after the 2D
// fit, as in Cohen, Beskow and Massaro (1998), Figures 5 and 6.
//
// - The chooser lists the observations; choosing one fetches it (GET /observations/{name}) and
//   shows the fitted pose.
// - Before and After set every parameter to the fit's start or its result, through the state the
//   sliders and the pasted JSON go through (ParamState.assign), so the sliders move too.
// - Overlay shows the observed points, the error vector of each from P to where its ray from the
//   origin first crosses the tongue as posed now (Q), and a sphere at P sized by |PQ|, in 3D
//   (scene/ObservationLayer.js) and on the sagittal panel. The errors are recomputed whenever the
//   tongue changes (the articulation's hook), never in a frame where nothing moved.
// - The panel reads out the RMS and the largest error of the outline (the 2D fit's own measure)
//   and of the surface; window.glasshead.observation reports them.
//
// ObservationControl.js holds the logic and no DOM, so it is tested in Node with a fake API;
// ObservationPanel is its view.

import { api as pageApi } from '../../api.js';
import { registerDebug } from '../../debug.js';
import { OBSERVATION_COLORS, ObservationLayer, sphereRadius } from '../../scene/ObservationLayer.js';
import { h } from '../shared/dom.js';
import { formatMm, ObservationControl } from './ObservationControl.js';
import { PhonemeChooser } from './PhonemeChooser.js';
import { fitTransform, SAGITTAL_BOX } from '../shared/SagittalPanel.js';

/** The sagittal panel's discs, as a share of the 3D spheres' radius. */
const PANEL_DISC = 0.5;

/**
 * Draw the outline's observed points, error vectors and spheres over the sagittal panel (the
 * panel's own transform; anterior to the left). Only z = 0 rays: the panel is the mid-sagittal plane.
 */
export function drawObservationSagittal( ctx, model, { width, height, box = SAGITTAL_BOX } ) {

	const view = fitTransform( box, width, height );
	const { points: p, q, signed, outlineCount } = model;
	ctx.save();
	ctx.lineWidth = 1.2;
	for ( let k = 0; k < outlineCount; k ++ ) {

		ctx.strokeStyle = signed[ k ] > 0 ? OBSERVATION_COLORS.beyond : OBSERVATION_COLORS.short;
		ctx.beginPath();
		ctx.moveTo( view.x( p[ 3 * k ] ), view.y( p[ 3 * k + 1 ] ) );
		ctx.lineTo( view.x( q[ 3 * k ] ), view.y( q[ 3 * k + 1 ] ) );
		ctx.stroke();

	}

	for ( let k = 0; k < outlineCount; k ++ ) {

		ctx.fillStyle = signed[ k ] > 0 ? OBSERVATION_COLORS.beyond : OBSERVATION_COLORS.short;
		ctx.beginPath();
		// Smaller than the 3D spheres (the panel is at about 2.5 px a mm), so the vectors still show between them.
		ctx.arc( view.x( p[ 3 * k ] ), view.y( p[ 3 * k + 1 ] ), Math.max( 1.2, PANEL_DISC * sphereRadius( signed[ k ] ) * view.scale ), 0, 2 * Math.PI );
		ctx.fill();

	}

	ctx.strokeStyle = OBSERVATION_COLORS.observed;
	ctx.lineWidth = 1.4;
	ctx.setLineDash( [ 4, 3 ] );
	ctx.beginPath();
	for ( let k = 0; k < outlineCount; k ++ ) ctx[ k === 0 ? 'moveTo' : 'lineTo' ]( view.x( p[ 3 * k ] ), view.y( p[ 3 * k + 1 ] ) );
	ctx.stroke();
	ctx.restore();

}

/** The state shown beside the switch. */
const STATE_TEXT = Object.freeze( { before: 'the fit\u2019s starting pose', after: 'the fitted pose', edited: 'a pose edited since: the errors follow the sliders' } );

export class ObservationPanel {

	/**
	 * @param {{ api?: object, articulation: object, viewer: object, head?: object|null,
	 *   sagittal?: { ctx, width, height }|null, redrawSagittal?: Function }} options the
	 *   workbench's client, articulation, viewer and head (its cutaway), and its sagittal canvas
	 *   with the function that redraws it (the overlay is drawn over it)
	 */
	constructor( { api = pageApi, articulation, viewer, head = null, sagittal = null, redrawSagittal = () => {} } ) {

		this.viewer = viewer;
		this.sagittal = sagittal;
		this.redrawSagittal = redrawSagittal;
		this.layer = new ObservationLayer( { isCut: () => Boolean( head?.cutaway ) } );
		viewer.scene.add( this.layer.group );
		this.control = new ObservationControl( { api, articulation, onUpdate: () => this.sync() } );
		this.error = null;

		this.select = h( 'select', { className: 'wb-select', 'aria-label': 'Observation', onChange: () => this.choose( this.select.value ) },
			h( 'option', { value: '' }, 'Loading the measured shapes…' ) );
		this.buttons = new Map( [ [ 'before', 'Before fit' ], [ 'after', 'After fit' ] ].map( ( [ key, label ] ) => [ key, h( 'button', {
			type: 'button', className: 'wb-toggle', 'aria-pressed': 'false', disabled: '', onClick: () => this.show( key ),
		}, label ) ] ) );
		this.overlayButton = h( 'button', { type: 'button', className: 'toggle wb-toggle', 'aria-pressed': 'true', disabled: '', onClick: () => this.toggleOverlay() }, 'Overlay' );
		this.readout = h( 'div', { className: 'wb-readout', role: 'status', 'aria-live': 'polite' } );
		this.legend = h( 'p', { className: 'wb-legend', hidden: '' },
			h( 'span', {}, swatch( OBSERVATION_COLORS.beyond ), ' tongue beyond the shape' ), h( 'span', {}, swatch( OBSERVATION_COLORS.short ), ' tongue short of it' ),
			h( 'span', { className: 'wb-note' }, 'The cutaway shows the outline; without it, the surface.' ) );
		this.plotLink = h( 'a', { className: 'wb-note', target: '_blank', rel: 'noopener', hidden: '' }, 'The fit\u2019s plot (SVG)' );
		this.errorText = h( 'p', { className: 'error wb-inline', role: 'alert', hidden: '' } );
		this.element = h( 'fieldset', { className: 'wb-box wb-observation', 'aria-label': 'Observation' },
			h( 'legend', {}, 'Observation' ),
			this.select,
			h( 'div', { className: 'wb-buttons', role: 'group', 'aria-label': 'Fit' }, ...this.buttons.values(), this.overlayButton ),
			this.readout,
			this.legend,
			this.plotLink,
			this.errorText,
		);
		this.unregister = registerDebug( 'observation', () => this.control.report() );
		this.load();

	}

	async load() {

		try {

			const entries = await this.control.list();
			this.select.replaceChildren(
				h( 'option', { value: '' }, entries.length ? 'Choose a measured shape…' : 'No measured shapes on this server' ),
				...entries.map( ( entry ) => h( 'option', { value: entry.name }, entry.label ?? entry.name ) ),
			);

		} catch ( error ) {

			this.select.replaceChildren( h( 'option', { value: '' }, 'No measured shapes' ) );
			this.showError( error.message );

		}

	}

	async choose( name ) {

		this.showError( null );
		try {

			await this.control.choose( name );

		} catch ( error ) {

			this.showError( error.message );

		}

		this.refresh();

	}

	show( which ) {

		this.showError( null );
		try {

			this.control.show( which );

		} catch ( error ) {

			this.showError( error.message );

		}

		this.refresh();

	}

	toggleOverlay() {

		this.control.setOverlay( ! this.control.overlay );
		this.refresh();

	}

	/** Redraw the sagittal panel under the overlay, then everything of the overlay. */
	refresh() {

		this.redrawSagittal();
		this.sync();

	}

	/** The buttons, the readout, the 3D layer and the sagittal overlay after any change. */
	sync() {

		const control = this.control;
		const report = control.report();
		const chosen = report.name !== null;
		for ( const [ key, button ] of this.buttons ) {

			button.disabled = ! chosen;
			button.setAttribute( 'aria-pressed', String( report.state === key ) );

		}

		this.overlayButton.disabled = ! chosen;
		this.overlayButton.setAttribute( 'aria-pressed', String( control.overlay ) );
		this.legend.hidden = ! chosen || ! control.overlay;
		const plot = chosen ? control.current.plot_url : null;
		if ( plot ) this.plotLink.setAttribute( 'href', plot );
		this.plotLink.hidden = ! plot;
		this.readout.replaceChildren( ...( chosen ? readoutLines( report ) : [] ) );
		if ( this.layer.model !== control.model ) {

			if ( control.model ) this.layer.setModel( control.model );
			else this.layer.clearParts();

		} else this.layer.update();

		this.layer.group.visible = chosen && control.overlay;
		if ( chosen && control.overlay && this.sagittal ) drawObservationSagittal( this.sagittal.ctx, control.model, this.sagittal );
		this.viewer.requestRender();

	}

	showError( message ) {

		this.error = message;
		this.errorText.textContent = message ?? '';
		this.errorText.hidden = ! message;

	}

	dispose() {

		this.unregister();
		this.control.dispose();
		this.layer.dispose();
		this.element.remove();

	}

}

function swatch( color ) {

	const element = h( 'span', { className: 'wb-swatch', 'aria-hidden': 'true' } );
	element.style.background = color; // through the CSSOM: the page's policy refuses style attributes
	return element;

}

/** The readout: what is shown, a small table of the outline's and the surface's errors, and the fit's own figure. */
function readoutLines( report ) {

	const row = ( name, part ) => h( 'tr', {}, h( 'th', { scope: 'row' }, name ), h( 'td', {}, formatMm( part.rmsMm ) ), h( 'td', {}, formatMm( part.maxMm ) ), h( 'td', {}, String( part.rays ) ) );
	const rows = [ row( 'Outline', report ) ];
	if ( report.surface ) rows.push( row( 'Surface', report.surface ) );
	const lines = [
		h( 'p', {}, `Showing ${ STATE_TEXT[ report.state ] }.` ),
		h( 'table', { className: 'wb-errors' },
			h( 'thead', {}, h( 'tr', {}, h( 'th', {}, 'Error' ), h( 'th', {}, 'RMS' ), h( 'th', {}, 'largest' ), h( 'th', {}, 'rays' ) ) ),
			h( 'tbody', {}, ...rows ) ),
	];
	if ( Number.isFinite( report.fitRmsMm ) ) lines.push( h( 'p', { className: 'wb-note' }, `The 2D fit reached ${ formatMm( report.fitRmsMm ) } RMS on the outline.` ) );
	const misses = report.misses + ( report.surface?.misses ?? 0 );
	if ( misses > 0 ) lines.push( h( 'p', { className: 'wb-note' }, `${ misses } rays miss the tongue (their vectors end at the origin).` ) );
	return lines;

}

/**
 * Put the "Phoneme target" and "Observation" groups at the top of the workbench's left column,
 * above the sliders they set. Returns a function that removes them.
 */
export function mountObservationPanels( view ) {

	const { api, articulation, viewer, head } = view;
	const phonemes = new PhonemeChooser( { api, state: articulation.state } );
	view.phonemeChooser = phonemes; // the cues read the chosen phoneme's glottis
	const observation = new ObservationPanel( {
		api, articulation, viewer, head, sagittal: view.sagittalCanvas, redrawSagittal: () => view.drawPanels(),
	} );
	view.parameters.element.before( phonemes.element, observation.element );
	return () => {

		phonemes.dispose();
		observation.dispose();

	};

}
