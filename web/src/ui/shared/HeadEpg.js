// Synthetic EPG in a view with a head: the electrodes on the 3D palate and a live flat
// palatogram beside the head, fed by the per-frame articulation's corrected tongue.
//
// attachHeadEpg( view ) needs view.head, view.viewer and view.stage, uses view.articulation when
// there is one (without it the display shows no contact, as for the rest tongue), and pushes its
// clean-up onto view.unregister. It never throws: a layout that cannot be loaded leaves the view
// as it was, with a warning.

import { registerDebug } from '../../debug.js';
import { EPG_COLUMNS, EPG_ELECTRODES, EPG_ROWS } from '../../core/constants.js';
import { Electrodes } from '../../scene/Electrodes.js';
import { createEpgLive } from '../../scene/EpgLive.js';
import { h } from './dom.js';
import { loadEpgLayout } from './loaders.js';
import { Palatogram } from './Palatogram.js';
import { keepCardClearOfLips } from './epgCardPlacement.js';
import './epg.css';

/** The rows of a frame without contact (emuR strings, R1 first). */
const EMPTY_ROWS = Object.freeze( Array.from( { length: EPG_ROWS }, () => '0'.repeat( EPG_COLUMNS ) ) );
/** Size of the live palatogram, CSS pixels. */
const PANEL_SIZE = Object.freeze( { width: 170, height: 196 } );

/** @param {{ api?: object }} options the HTTP client the layout is loaded through */
export async function attachHeadEpg( view, { api } = {} ) {

	let layout;
	try {

		layout = await loadEpgLayout( { api } );

	} catch ( error ) {

		console.warn( `Glasshead: no EPG display; the electrode layout did not load: ${ error.message }` );
		return null;

	}

	if ( ! view.viewer || ! view.head ) return null; // unmounted while loading
	const articulation = view.articulation ?? null;
	const live = articulation
		? createEpgLive( { layout, tongueTriangles: articulation.triangles, vertexCount: articulation.vertexCount } )
		: null;

	const electrodes = new Electrodes( layout.grids.reading62, { clippingPlanes: [ view.head.clipPlane ] } );
	view.head.group.add( electrodes.group );
	const palatogram = new Palatogram( { ...PANEL_SIZE, label: 'Synthetic EPG', ariaLabel: 'Live synthetic palatogram, front at the top' } );
	const percent = h( 'span', { className: 'epg-percent' }, '0% contact' );
	const panel = h( 'figure', { className: 'epg-overlay', 'aria-label': 'Synthetic EPG' }, palatogram.element, h( 'figcaption', {}, percent ) );
	view.stage.append( panel );

	const show = ( frame, contacted ) => {

		electrodes.show( frame );
		palatogram.set( frame );
		percent.textContent = `${ Math.round( 100 * contacted / EPG_ELECTRODES ) }% contact`;
		view.viewer?.requestRender();

	};

	const cleanups = [ keepCardClearOfLips( view, panel ) ];
	if ( live ) {

		cleanups.push( live.onUpdate( () => show( live.frame, live.contacted ) ) );
		cleanups.push( articulation.onCorrected( ( positions ) => live.update( positions ) ) );
		cleanups.push( live.registerDebug() );
		live.update( articulation.positions );

	} else {

		show( null, 0 );
		cleanups.push( registerDebug( 'epg', () => ( { source: 'rest tongue', rows: EMPTY_ROWS, contacted: 0, percent: 0 } ) ) );

	}

	// The see-through pass follows the skin: on while it is transparent or cut away.
	cleanups.push( view.viewer.onFrame( () => electrodes.setXray( view.head.transparency > 0 || view.head.cutaway ) ) );
	cleanups.push( registerDebug( 'electrodes', () => ( view.viewer ? electrodes.probe( view.viewer ) : null ) ) );
	const dispose = () => {

		for ( const cleanup of cleanups ) cleanup();
		electrodes.dispose();
		panel.remove();

	};

	view.unregister.push( dispose );
	return { live, electrodes, palatogram, panel, dispose };

}
