// Synthetic EPG of the live tongue: the per-frame articulation hands over the corrected tongue,
// this computes which electrodes it touches (core/epgContacts.js) and the EPG indices
// (core/epgIndices.js), and tells its listeners (the 3D electrodes, the flat palatogram).
//
//   const epg = createEpgLive( { layout, tongueTriangles, vertexCount } );
//   articulation.onCorrected( ( positions ) => epg.update( positions ) );
//
// `layout` holds the grids of the layout file (GET /api/v1/epg/layout answers one grid of it; the
// views load both with ui/shared/loaders.js loadEpgLayout). Nothing is allocated per frame: the frames
// and indices are preallocated and the listeners get the same arrays every time.

import { registerDebug } from '../debug.js';
import { EPG_ELECTRODES } from '../core/constants.js';
import { contactRows, createContactModel, electrodeContacts } from '../core/epgContacts.js';
import { epgIndices, INDEX_SLOTS, INDEX_STRIDE, SLOT_PERCENT } from '../core/epgIndices.js';

/**
 * @param {{ layout: { grids: { reading62: object, dense96?: object } }, tongueTriangles: Uint32Array,
 *   vertexCount: number, dense?: boolean }} options `dense` also computes the 96-electrode grid
 */
export function createEpgLive( { layout, tongueTriangles, vertexCount, dense = false } ) {

	const reading = createContactModel( layout.grids.reading62, tongueTriangles, vertexCount );
	const denseModel = dense && layout.grids.dense96 ? createContactModel( layout.grids.dense96, tongueTriangles, vertexCount ) : null;
	const live = {
		model: reading,
		denseModel,
		/** Reading frame: 64 cells, row-major, R1 first (R1 corners always 0). */
		frame: new Uint8Array( reading.cells ),
		/** Dense frame (12 x 8), when asked for. */
		denseFrame: denseModel ? new Uint8Array( denseModel.cells ) : null,
		/** emuR indices of the Reading frame, INDEX_SLOTS order. */
		indices: new Float64Array( INDEX_STRIDE ),
		contacted: 0,
		updates: 0,
		lastMs: 0,
		listeners: new Set(),

		/** Contacts and indices of a corrected tongue (Float32Array, xyz per vertex). */
		update( positions ) {

			const start = performance.now();
			this.contacted = electrodeContacts( reading, positions, this.frame );
			if ( denseModel ) electrodeContacts( denseModel, positions, this.denseFrame );
			epgIndices( this.frame, 0, this.indices );
			this.updates ++;
			this.lastMs = performance.now() - start;
			for ( const listener of this.listeners ) listener( this );
			return this.frame;

		},

		/** No tongue (or the rest tongue before the articulation loads): no contact. */
		clear() {

			this.frame.fill( 0 );
			this.denseFrame?.fill( 0 );
			this.contacted = 0;
			epgIndices( this.frame, 0, this.indices );
			for ( const listener of this.listeners ) listener( this );

		},

		/** Call fn( live ) after every update; returns a function that removes it. */
		onUpdate( fn ) {

			this.listeners.add( fn );
			return () => this.listeners.delete( fn );

		},

		/** emuR-style rows of the Reading frame: 8 strings of '0'/'1', R1 first. */
		rows() {

			return contactRows( reading, this.frame );

		},

		/** What window.glasshead.epg reports. */
		report() {

			const indices = {};
			INDEX_SLOTS.forEach( ( name, k ) => {

				indices[ name ] = Math.round( this.indices[ k ] * 1e6 ) / 1e6;

			} );
			return {
				source: 'live',
				grid: reading.grid,
				electrodes: EPG_ELECTRODES,
				rows: this.rows(),
				contacted: this.contacted,
				percent: Math.round( this.indices[ SLOT_PERCENT ] * 1000 ) / 1000,
				dense: denseModel ? contactRows( denseModel, this.denseFrame ) : null,
				indices,
				updates: this.updates,
				ms: Math.round( this.lastMs * 1000 ) / 1000,
			};

		},

		/** Add `epg` to window.glasshead; returns the function that removes it. */
		registerDebug() {

			return registerDebug( 'epg', () => this.report() );

		},

	};
	live.clear();
	return live;

}
