// The speech player's panels beside the head: the 2D diagram of the vocal tract (redrawn with
// every recompute of the articulation, so it follows the clock), the cue switches (the workbench's
// WorkbenchCues, driving the cue layer in the 3D scene, with the glottis of the phone being
// said) and the dominance plot.

import { DiagramSection } from '../../scene/DiagramSection.js';
import { loadPhonemeList } from '../shared/loaders.js';
import { h } from '../shared/dom.js';
import { HiDpiCanvas } from '../shared/hidpiCanvas.js';
import { drawDiagram } from '../shared/DiagramPanel.js';
import { DominancePlot } from './DominancePlot.js';
import { WorkbenchCues } from '../shared/WorkbenchCues.js';

/** Sizes of the canvases, CSS pixels (the side panel is 330 px wide). */
const DIAGRAM_SIZE = Object.freeze( [ 300, 280 ] );
const DOMINANCE_SIZE = Object.freeze( [ 300, 170 ] );
const DIAGRAM_PARTS = Object.freeze( [ 'pharynx', 'larynx', 'palate', 'mandible', 'velum', 'upperLip', 'lowerLip', 'tongue' ] );

/** A canvas of `width` x `height` CSS pixels, sharp on high-density screens. */
function canvas( [ width, height ], ariaLabel ) {

	return new HiDpiCanvas( { width, height, ariaLabel, className: 'sp-canvas' } );

}

export class SpeechPanels {

	/** @param {{ head: object, viewer: object, articulation: object, landmarks: object|null, api?: object }} parts */
	constructor( { head, viewer, articulation, landmarks, api } ) {

		this.unregister = [];
		this.diagramCanvas = canvas( DIAGRAM_SIZE, 'Diagram: the vocal tract cut at the mid-sagittal plane' );
		this.diagram = new DiagramSection( head, { landmarks } );
		this.diagramParts = Object.fromEntries( DIAGRAM_PARTS.map( ( key ) => [ key, this.diagram.parts( key ) ] ) );
		this.unregister.push( this.diagram.registerDebugField(), articulation.onCorrected( () => this.drawDiagram() ) );
		this.drawDiagram();
		/** Whether the voice sounds at the clock's time (the utterance's voicing cue), set by the player. */
		this.voiced = true;
		/** The ARPAbet symbol of the phone at the clock's time (null in none), set by the player. */
		this.phoneSymbol = null;
		this.featuresBySymbol = new Map();
		this.loadFeatures( api );
		this.cues = new WorkbenchCues( {
			viewer, articulation, diagram: this.diagram, landmarks, voiced: () => this.voiced,
			sound: () => this.featuresBySymbol.get( this.phoneSymbol ) ?? null,
		} );
		this.cues.element.className = 'sp-buttons';
		this.dominance = new DominancePlot( canvas( DOMINANCE_SIZE, 'Dominance of each phoneme over time for the chosen parameter' ), articulation.state );
		const section = ( title, ...content ) => h( 'section', { className: 'sp-section' }, h( 'h2', { className: 'sp-heading' }, title ), ...content );
		this.sections = [
			section( 'Diagram', this.diagramCanvas.element ),
			section( 'Air and voice', this.cues.element ),
			section( 'Dominance', this.dominance.element ),
		];

	}

	/** Each phoneme's voicing and manner, from GET /phonemes, for the cues' air (none until then). */
	async loadFeatures( api ) {

		try {

			const body = await loadPhonemeList( { api } );
			for ( const { arpabet, voiced, manner } of body?.phonemes ?? [] ) this.featuresBySymbol.set( arpabet, { voiced, manner } );

		} catch ( error ) {

			console.warn( `Glasshead: the cues' air ignores the phones; the phonemes did not load: ${ error.message }` );

		}

	}

	drawDiagram() {

		this.diagram.update();
		drawDiagram( this.diagramCanvas.ctx, { parts: this.diagramParts, air: this.diagram.polygon, constriction: this.diagram.constriction() }, this.diagramCanvas );

	}

	dispose() {

		for ( const unregister of this.unregister ) unregister();
		this.cues.dispose();
		for ( const element of this.sections ) element.remove();

	}

}
