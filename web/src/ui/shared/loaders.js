// What the views load from the API, all through the one HTTP client (api.js): the anatomy meshes,
// the tongue rig with the collision tables and the face rig, the electrode layouts and the phoneme
// targets. Scene
// objects are handed what these return and fetch nothing themselves. Every function takes the
// client as `api` (tests pass one made by createApi( { fetchImpl } )).

import { GLTFLoader } from 'three/addons/loaders/GLTFLoader.js';
import { api as pageApi } from '../../api.js';
import { EPG_GRIDS } from '../../core/constants.js';
import { checkCollisionTablesInfo, decodeCollisionTables } from '../../core/tables.js';
import { createArticulation } from '../../scene/Articulation.js';
import { geometryFromGltf } from '../../scene/gltfGeometry.js';
import { labelEntries } from './labelPlacement.js';

/** A mesh of GET /anatomy that could not be loaded; names it and says why. */
export class MeshLoadError extends Error {

	constructor( entry, cause ) {

		super( `Could not load the mesh "${ entry.name }" from ${ entry.url }: ${ cause?.message ?? cause }`, { cause } );
		this.name = 'MeshLoadError';
		this.mesh = entry.name;

	}

}

/**
 * Load every entry ({ name, url, role } of GET /anatomy) and add it to `head` in the listed order.
 * onProgress( loaded, total, name ) is called as each file arrives. Rejects with a MeshLoadError
 * naming the first mesh that failed.
 */
export async function loadAnatomy( head, entries, { api = pageApi, onProgress = () => {}, loader = new GLTFLoader() } = {} ) {

	let loaded = 0;
	const geometries = await Promise.all( entries.map( async ( entry ) => {

		let geometry;
		try {

			geometry = geometryFromGltf( await loader.parseAsync( await api.getBinary( entry.url ), '' ) );

		} catch ( error ) {

			throw new MeshLoadError( entry, error );

		}

		loaded ++;
		onProgress( loaded, entries.length, entry.name );
		return geometry;

	} ) );

	entries.forEach( ( entry, i ) => head.addPart( entry, geometries[ i ] ) );
	head.finishLoading();
	return head;

}

/**
 * The collision tables, decoded: GET /collision/tables gives the header and the URL of the binary;
 * a server whose tables have another format version is refused before the binary is downloaded.
 */
export async function loadCollisionTables( { api = pageApi } = {} ) {

	const info = checkCollisionTablesInfo( await api.get( 'collision/tables' ) );
	return decodeCollisionTables( await api.getBinary( info.url ) );

}

/**
 * What scene/Articulation.js createArticulation() is handed: the tongue rig definition (rejects
 * without it), the collision tables, the face rig and the velum rig definitions, each null with
 * its error message when it could not be had. `tables: false` leaves the tables out (null, with
 * no error): loadArticulation's 'whenMoved' loads them later.
 * @returns {Promise<{ definition: object, tables: object|null, tablesError: string|null,
 *   face: object|null, faceRigError: string|null, velum: object|null, velumError: string|null }>}
 */
export async function loadArticulationData( { api = pageApi, tables: withTables = true } = {} ) {

	const [ definition, tables, face, velum ] = await Promise.all( [
		api.get( 'tongue/rig' ),
		withTables ? loadCollisionTables( { api } ).catch( ( error ) => error ) : null,
		api.get( 'face/rig' ).catch( ( error ) => error ),
		api.get( 'velum/rig' ).catch( ( error ) => error ),
	] );
	return {
		definition,
		tables: tables instanceof Error ? null : tables,
		tablesError: tables instanceof Error ? tables.message : null,
		face: face instanceof Error ? null : face,
		faceRigError: face instanceof Error ? face.message : null,
		velum: velum instanceof Error ? null : velum,
		velumError: velum instanceof Error ? velum.message : null,
	};

}

/**
 * Load the articulation's data and put the parametric tongue and the face rig into `head`.
 * `tables: 'whenMoved'` (the head view) leaves the collision tables (2.9 MB, 1.25 MB gzipped, the
 * largest download of the page) until the tongue first leaves its rest pose, which needs no
 * correction; the workbench and speech views move the tongue at once and load them with the rest.
 */
export async function loadArticulation( head, viewer, { api = pageApi, tables = 'now' } = {} ) {

	const lazy = tables === 'whenMoved';
	const articulation = createArticulation( head, viewer, await loadArticulationData( { api, tables: ! lazy } ) );
	if ( lazy && viewer ) loadTablesWhenMoved( articulation, viewer, { api } );
	return articulation;

}

/**
 * Give `articulation` its collision tables once its parameters first change (read on the
 * viewer's frames), and correct the tongue again when they arrive; a failure is kept in
 * articulation.tablesError, as at load. Stops with the articulation's dispose().
 */
export function loadTablesWhenMoved( articulation, viewer, { api = pageApi } = {} ) {

	const restVersion = articulation.state.version;
	let live = true;
	// The hook only watches: it returns false so that a still head draws no frames.
	const stop = viewer.onFrame( () => {

		if ( articulation.state.version === restVersion ) return false;
		stop();
		loadCollisionTables( { api } ).then( ( tables ) => {

			if ( ! live ) return;
			articulation.tables = tables;
			articulation.update( true );
			viewer.requestRender();

		}, ( error ) => {

			articulation.tablesError = error.message;
			console.warn( `Glasshead: the tongue is not kept out of the palate; the collision tables did not load: ${ error.message }` );

		} );
		return false;

	} );
	articulation.unregister.push( () => {

		live = false;
		stop();

	} );

}

/**
 * The teaching landmarks (GET /anatomy/landmarks): the parts and places of articulation the label
 * layer names; a document of another format version is refused.
 */
export async function loadLandmarks( { api = pageApi } = {} ) {

	const document = await api.get( 'anatomy/landmarks' );
	labelEntries( document ); // throws on another format version
	return document;

}

/**
 * The electrode layouts of every grid: { grids: { reading62, dense96 }, contact, midline }.
 * @param {{ api?: object, grids?: string[] }} options `grids` to load fewer
 */
export async function loadEpgLayout( { api = pageApi, grids = EPG_GRIDS } = {} ) {

	const layouts = await Promise.all( grids.map( ( grid ) => api.get( `epg/layout?grid=${ encodeURIComponent( grid ) }` ) ) );
	const byName = Object.fromEntries( grids.map( ( grid, k ) => [ grid, layouts[ k ] ] ) );
	const first = layouts[ 0 ];
	return { grids: byName, contact: first?.contact, midline: first?.midline };

}

/**
 * The phoneme targets (GET /phonemes): { format_version, count, phonemes: [{ arpabet, ipa, kind,
 * examples, source: { kind, shapes, rms_mm }, url }] }.
 */
export async function loadPhonemeList( { api = pageApi } = {} ) {

	return api.get( 'phonemes' );

}

/**
 * One phoneme's target (GET /phonemes/{symbol}, ARPAbet or IPA): its parameters of every rig, its
 * synthetic EPG (epg.rows, R1 first; epg.indices), contexts, source, examples and features.
 */
export async function loadPhonemeTarget( symbol, { api = pageApi } = {} ) {

	return api.get( `phonemes/${ encodeURIComponent( symbol ) }` );

}
