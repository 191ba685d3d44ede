// The workbench's acoustics: the head's own tract as a tube (scene/TractAcoustics.js), its area
// function drawn from the glottis to the lips, and its F1 and F2 as a dot on the vowel chart the
// listening page shows a learner (the men's vowel norms, as the head is a man's), with F1 to F3
// written out. Redrawn after each frame's diagram section.

import { TractAcoustics, TRACT_SECTION_URL } from '../../scene/TractAcoustics.js';
import { VowelChart } from '../listen/ListenDisplays.js';
import { NORMS_URL } from '../listen/listenScales.js';
import { h } from '../shared/dom.js';
import { drawAreaFunction } from '../shared/AreaFunctionPlot.js';
import { HiDpiCanvas } from '../shared/hidpiCanvas.js';

/** The norms' group the head is drawn against. */
export const HEAD_GROUP = 'man';

/** The readout of a summary ({ formants, closed }) of TractAcoustics. */
export function formantText( summary ) {

	if ( ! summary ) return 'Formants: loading…';
	const [ f1, f2, f3 ] = summary.formants;
	const hz = ( f ) => ( f === null ? '–' : `${ f }` );
	const peaks = `F1 ${ hz( f1 )} Hz · F2 ${ hz( f2 ) } Hz · F3 ${ hz( f3 ) } Hz`;
	if ( summary.closed && summary.nasalAt ) return `The mouth is shut and the sound goes through the nose (a nasal murmur): ${ peaks }`;
	if ( summary.closed ) return 'The tract is shut here: no vowel formants (a stop).';
	return summary.nasalAt ? `${ peaks }, with the nose open` : peaks;

}

export class FormantPanel {

	/**
	 * @param {{ api: object, diagram: object, state: object, velumRig?: object|null }} options the
	 *   HTTP client, the DiagramSection, the ParamState, and the velum rig that opens the nose
	 */
	constructor( { api, diagram, state, velumRig = null } ) {

		this.api = api;
		this.velumRig = velumRig;
		this.diagram = diagram;
		this.state = state;
		this.tract = null;
		this.chart = new VowelChart( { width: 380, height: 300 } );
		this.chart.canvas.element.classList.add( 'wb-canvas' );
		this.readout = h( 'p', { className: 'wb-formants-text', 'aria-live': 'off' }, formantText( null ) );
		this.areaCanvas = new HiDpiCanvas( { width: 380, height: 150, ariaLabel: 'The area function: the air\'s cross-section from the glottis to the lips', className: 'wb-canvas' } );
		this.element = h( 'section', { className: 'wb-formants', 'aria-label': 'Formants of the head\'s tract' },
			h( 'h2', { className: 'wb-formants-title' }, 'Formants of the head\'s tract' ),
			this.areaCanvas.element, this.chart.element, this.readout,
			h( 'p', { className: 'wb-formants-note' }, 'The dot is the head\'s vowel as its tract sounds; the ellipses are men\'s vowels (Peterson and Barney, 1952).' ) );
		this.removeDebug = null;

	}

	/** Load the tract's section and the norms; false (with the reason shown) when they fail. */
	async load() {

		try {

			const [ section, norms ] = await Promise.all( [ this.api.get( TRACT_SECTION_URL ), this.api.get( NORMS_URL ) ] );
			this.chart.setNorms( norms?.groups?.[ HEAD_GROUP ] ?? {} );
			this.tract = new TractAcoustics( this.diagram, section, this.state, { velumRig: this.velumRig } );
			this.removeDebug = this.tract.registerDebugField();
			this.update();
			return true;

		} catch ( error ) {

			this.readout.textContent = `The formants are not available: ${ error.message ?? error }`;
			return false;

		}

	}

	/** Recompute from the diagram's current section and redraw (after each diagram update). */
	update() {

		if ( ! this.tract ) return;
		const summary = this.tract.update().summary();
		const [ f1, f2 ] = summary.formants;
		this.chart.draw( [], summary.closed ? null : { f1, f2, zone: null } );
		const ctx = this.areaCanvas.clear();
		if ( ctx ) drawAreaFunction( ctx, this.tract.tube, this.areaCanvas, this.tract.nasal );
		this.readout.textContent = formantText( summary );

	}

	dispose() {

		this.removeDebug?.();

	}

}
