// The workbench's cue controls (a "Cues" group, apart from the articulation parameters): Cues
// shows or hides the whole layer; Voicing, Nasal airflow (shown only while the nasal port is
// open) and Oral airflow switch each cue. Drives scene/CueLayer.js from the diagram's
// constriction (its width and place: a closure stops the oral flow there) and the velum's port,
// animates it while it is shown (a hidden layer asks for no frames) and reports
// window.glasshead.cues.

import { registerDebug } from '../../debug.js';
import { CueLayer } from '../../scene/CueLayer.js';
import { h } from './dom.js';

/** The toggles: key, label. Cues are off by default; each cue is on, ready for when they show. */
const TOGGLES = Object.freeze( [ [ 'visible', 'Cues' ], [ 'voicing', 'Voicing' ], [ 'nasal', 'Nasal airflow' ], [ 'oral', 'Oral airflow' ] ] );
export const CUE_DEFAULTS = Object.freeze( { visible: false, voicing: true, nasal: true, oral: true } );

/** A landmark's x y by name, or null. */
function landmark( landmarks, name ) {

	const entry = ( landmarks?.landmarks ?? [] ).find( ( e ) => e.name === name );
	return entry ? entry.position.slice( 0, 2 ) : null;

}

export class WorkbenchCues {

	/**
	 * @param {{ viewer: object, articulation: object, diagram: object, landmarks: object|null }}
	 *   parts the workbench's viewer, articulation (its state and velum), DiagramSection (its
	 *   midline and live constriction) and GET /anatomy/landmarks (the glottis and the nasal port);
	 *   `voiced()` whether the voice sounds now (default: always); `sound()` the features of the
	 *   phoneme made now (CueLayer's; default: none)
	 */
	constructor( { viewer, articulation, diagram, landmarks, voiced = () => true, sound = undefined } ) {

		this.viewer = viewer;
		this.unregister = [];
		const glottis = landmark( landmarks, 'glottis' );
		this.element = h( 'div', { className: 'wb-buttons wb-cues', role: 'group', 'aria-label': 'Cues' } );
		if ( ! glottis || ! diagram.midline ) return; // no landmarks or no airway: no cues
		const velum = articulation.velum ?? null;
		this.layer = new CueLayer( {
			glottis, port: landmark( landmarks, 'nasal_port' ), midline: diagram.midline.points,
			constriction: diagram.result, portArea: () => velum?.portArea ?? 0, voiced, sound,
		} );
		this.layer.set( CUE_DEFAULTS );
		viewer.scene.add( this.layer.group );
		this.buttons = new Map( TOGGLES.map( ( [ key, label ] ) => [ key, h( 'button', {
			type: 'button', className: 'toggle wb-toggle', 'aria-pressed': String( CUE_DEFAULTS[ key ] ),
			onClick: () => this.toggle( key ),
		}, label ) ] ) );
		this.element.append( ...this.buttons.values() );
		this.unregister.push(
			viewer.onFrame( ( dt, t ) => this.layer.update( t ) ),
			articulation.onCorrected( () => this.sync() ), // after the velum and the constriction follow a change
			registerDebug( 'cues', () => {

				this.layer.update( performance.now() / 1000 ); // current, between frames too
				return this.layer.state();

			} ),
		);
		this.sync();

	}

	toggle( key ) {

		this.layer.set( { [ key ]: ! this.layer.cues[ key ] } );
		this.sync();
		this.viewer.requestRender(); // draws the layer shown or hidden, at least once

	}

	/** The buttons' state; the nasal one only while the port is open and the layer shown. */
	sync() {

		const { cues } = this.layer;
		this.layer.update( performance.now() / 1000 );
		for ( const [ key, button ] of this.buttons ) {

			button.setAttribute( 'aria-pressed', String( cues[ key ] ) );
			if ( key !== 'visible' ) button.hidden = ! cues.visible || ( key === 'nasal' && this.layer.state().nasalStrength === 0 );

		}

	}

	dispose() {

		for ( const unregister of this.unregister ) unregister();
		this.layer?.dispose();
		this.element.remove();

	}

}
