// The vocal tract's mid-sagittal section for the flat diagram, recut with every articulation
// frame, and the narrowest constriction read from it (window.glasshead.constriction).
//
// Parts and how they move (see Articulation.js):
//   - deforming, recut every frame: the tongue (posed and collision corrected), the velum (posed
//     by velum_opening), the lips (posed in place by the face rig, or riding on the jaw);
//   - rigid, cut once and mapped by their group's matrix every frame: the mandible (jaw pose);
//   - still, cut once: the maxilla with the upper teeth, the pharyngeal wall, the larynx
//     cartilages and the airway.
// The section kernels are core/midSection.js and core/constriction.js; nothing is allocated per
// frame.

import { airwayPolygon, chainSegments } from '../core/sectionPolygon.js';
import { planeSectionSegments } from '../core/section.js';
import { createSectionPart, cutSection, posePoints, poseFromMatrix } from '../core/midSection.js';
import {
	CONSTRICTION_AT, CONSTRICTION_FLOOR, CONSTRICTION_FOUND, CONSTRICTION_LENGTH, CONSTRICTION_PLACE,
	CONSTRICTION_ROOF, CONSTRICTION_WIDTH, findConstriction, tractMidline,
} from '../core/constriction.js';
import { registerDebug } from '../debug.js';

/** The diagram's parts: key, scene meshes, how they move. */
export const DIAGRAM_PARTS = Object.freeze( [
	{ key: 'airway', meshes: [ 'airway' ], motion: 'still' },
	{ key: 'pharynx', meshes: [ 'pharynx' ], motion: 'still' },
	{ key: 'larynx', meshes: [ 'thyroid', 'cricoid', 'arytenoid_left', 'arytenoid_right' ], motion: 'still' },
	{ key: 'palate', meshes: [ 'maxilla' ], motion: 'still' },
	{ key: 'mandible', meshes: [ 'mandible' ], motion: 'rigid' },
	{ key: 'velum', meshes: [ 'velum_rest' ], motion: 'deforming' },
	{ key: 'tongue', meshes: [ 'tongue_rest' ], motion: 'deforming' },
	{ key: 'upperLip', meshes: [ 'upper_lip' ], motion: 'deforming' },
	{ key: 'lowerLip', meshes: [ 'lower_lip' ], motion: 'deforming' },
] );

/** The floor and the roof of the constriction search. */
const FLOOR = Object.freeze( [ 'tongue', 'lowerLip' ] );
const ROOF = Object.freeze( [ 'palate', 'velum', 'upperLip' ] );

function round2( value ) {

	return Math.round( value * 100 ) / 100;

}

export class DiagramSection {

	/**
	 * @param {object} head the Head, its meshes loaded and the articulation attached
	 * @param {{ landmarks?: object|null }} options GET /anatomy/landmarks (its places of
	 *   articulation name the constriction; null: no names)
	 */
	constructor( head, { landmarks = null } = {} ) {

		this.head = head;
		/** Section parts by mesh name, each with { key, motion, mesh, geometry, pose }. */
		this.meshes = [];
		for ( const spec of DIAGRAM_PARTS ) {

			for ( const name of spec.meshes ) {

				const scenePart = head.part( name );
				if ( ! scenePart ) continue;
				this.meshes.push( this.createMesh( spec, name, scenePart ) );

			}

		}

		const byKey = ( keys ) => this.meshes.filter( ( m ) => keys.includes( m.key ) ).map( ( m ) => m.section );
		this.floor = byKey( FLOOR );
		this.roof = byKey( ROOF );
		const airway = head.part( 'airway' );
		this.polygon = head.air?.polygon ?? ( airway ? polygonOf( airway.geometry ) : null );
		this.midline = this.polygon ? tractMidline( this.polygon.upper, this.polygon.lower ) : null;
		const places = ( landmarks?.landmarks ?? [] ).filter( ( entry ) => entry.kind === 'place' );
		this.placeNames = places.map( ( entry ) => entry.name );
		this.places = places.length ? Float64Array.from( places.flatMap( ( entry ) => entry.position.slice( 0, 2 ) ) ) : null;
		this.result = new Float64Array( CONSTRICTION_LENGTH );
		this.updates = 0;
		this.lastMs = 0;
		for ( const mesh of this.meshes ) cutSection( mesh.section, mesh.geometry.attributes.position.array, this.poseOf( mesh ) );
		this.update();

	}

	createMesh( spec, name, scenePart ) {

		const geometry = scenePart.geometry;
		const count = geometry.attributes.position.count;
		// A posed mesh may name the only triangles that can reach the plane (VelumPose does).
		const index = geometry.userData.midplaneTriangles ?? ( geometry.index ? geometry.index.array : Uint32Array.from( { length: count }, ( _, k ) => k ) );
		return { key: spec.key, motion: spec.motion, name, scenePart, geometry, section: createSectionPart( index, count ), pose: new Float64Array( 12 ) };

	}

	/** The mesh's group matrix as a pose, or null when its group is not posed by hand. */
	poseOf( mesh ) {

		const group = mesh.scenePart.group;
		return group && ! group.matrixAutoUpdate ? poseFromMatrix( group.matrix.elements, mesh.pose ) : null;

	}

	/** Recut the moving parts and find the constriction (after each articulation frame). */
	update() {

		const start = performance.now();
		this.cut();
		this.findConstriction();
		this.updates ++;
		this.lastMs = performance.now() - start;
		return this;

	}

	/** Recut the deforming parts and pose the rigid ones: the section of this frame. */
	cut() {

		for ( const mesh of this.meshes ) {

			if ( mesh.motion === 'still' ) continue;
			const pose = this.poseOf( mesh );
			if ( mesh.motion === 'rigid' ) posePoints( mesh.section, pose );
			else cutSection( mesh.section, mesh.scenePart.geometry.attributes.position.array, pose );

		}

		return this;

	}

	/** The narrowest gap of the section as cut (into this.result). */
	findConstriction() {

		findConstriction( this.floor, this.roof, this.midline, this.places, this.result );
		return this;

	}

	/** The section parts of a key (e.g. 'larynx' has four). */
	parts( key ) {

		return this.meshes.filter( ( mesh ) => mesh.key === key ).map( ( mesh ) => mesh.section );

	}

	/** What window.glasshead.constriction reports: width and place (mm), the place's name. */
	constriction() {

		const r = this.result;
		if ( ! r[ CONSTRICTION_FOUND ] ) return null;
		const place = r[ CONSTRICTION_PLACE ];
		return {
			widthMm: round2( r[ CONSTRICTION_WIDTH ] ),
			atMm: round2( r[ CONSTRICTION_AT ] ),
			place: place >= 0 ? this.placeNames[ place ] : null,
			floor: [ round2( r[ CONSTRICTION_FLOOR ] ), round2( r[ CONSTRICTION_FLOOR + 1 ] ) ],
			roof: [ round2( r[ CONSTRICTION_ROOF ] ), round2( r[ CONSTRICTION_ROOF + 1 ] ) ],
		};

	}

	/** Add window.glasshead.constriction; returns the function that removes it. */
	registerDebugField() {

		return registerDebug( 'constriction', () => this.constriction() );

	}

}

/** The airway's air polygon (sectionPolygon.js) when no air layer has it; once, allocating. */
function polygonOf( geometry ) {

	const positions = geometry.attributes.position.array;
	const index = geometry.index ? geometry.index.array : null;
	const segments = new Float32Array( 6 * ( index ? index.length / 3 : positions.length / 9 ) );
	const count = planeSectionSegments( positions, index, 0, segments );
	try {

		return airwayPolygon( chainSegments( segments, count ) );

	} catch {

		return null;

	}

}

export { CONSTRICTION_AT, CONSTRICTION_FLOOR, CONSTRICTION_ROOF, CONSTRICTION_WIDTH };
