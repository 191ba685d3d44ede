// The velum in the scene, posed by velum_opening (core/velum.js): the rest velum's mesh takes the
// blended positions, its normals and section follow, and window.glasshead.velum reports the
// opening and the nasal port's smallest cross-section. The raised pose joins the cutaway's
// cavity (AirLayer.js), so that the port shows as air when the velum lowers. Nothing is
// allocated per frame.

import { BufferAttribute, BufferGeometry } from 'three';
import { createVelumRig, nasalPortArea, poseVelum } from '../core/velum.js';
import { VELUM_PARAMETER } from '../core/constants.js';
import { vertexNormals } from '../core/meshVolume.js';
import { registerDebug } from '../debug.js';

/** The scene mesh the velum rig poses. */
export const VELUM_PART = 'velum_rest';

/** Largest distance (mm) between the rig's rest pose and the loaded mesh: the same vertex order. */
const REST_TOLERANCE_MM = 0.01;

export class VelumPose {

	/**
	 * @param {object} definition the velum rig (GET /velum/rig)
	 * @param {object} head the Head, with its VELUM_PART loaded
	 * @param {object} state the ParamState, with VELUM_PARAMETER among its parameters
	 */
	constructor( definition, head, state ) {

		const rig = createVelumRig( definition );
		const part = head.part( VELUM_PART );
		if ( ! part ) throw new Error( `the velum rig needs the mesh "${ VELUM_PART }"` );
		const loaded = part.geometry.getAttribute( 'position' );
		if ( loaded.count !== rig.vertexCount ) throw new Error( `"${ VELUM_PART }" has ${ loaded.count } vertices; the velum rig has ${ rig.vertexCount }` );
		for ( let i = 0; i < 3 * rig.vertexCount; i ++ ) {

			if ( Math.abs( loaded.array[ i ] - rig.rest[ i ] ) > REST_TOLERANCE_MM ) throw new Error( `"${ VELUM_PART }" is not the velum rig's rest pose (vertex ${ Math.floor( i / 3 ) })` );

		}

		this.rig = rig;
		this.head = head;
		this.index = state.indexOf( VELUM_PARAMETER );
		this.positions = new Float32Array( 3 * rig.vertexCount );
		this.normals = new Float32Array( 3 * rig.vertexCount );
		this.sums = new Float64Array( 3 * rig.vertexCount );
		this.triangles = Uint32Array.from( part.geometry.index.array );
		this.opening = NaN;
		this.portArea = 0;

		const geometry = new BufferGeometry();
		geometry.setAttribute( 'position', new BufferAttribute( this.positions, 3 ) );
		geometry.setAttribute( 'normal', new BufferAttribute( this.normals, 3 ) );
		geometry.setIndex( new BufferAttribute( this.triangles, 1 ) );
		this.geometry = geometry;
		this.pose( state.values );
		const old = part.geometry;
		head.setGeometry( VELUM_PART, geometry );
		old.dispose();
		head.air?.addVelumPose( rig.raised, geometry.index );

	}

	/** Pose the velum for the state's values (does nothing when the opening is unchanged). */
	pose( values ) {

		const opening = values[ this.index ];
		if ( opening === this.opening ) return;
		this.opening = opening;
		poseVelum( this.rig, opening, this.positions );
		this.portArea = nasalPortArea( this.rig, opening );
		vertexNormals( this.positions, this.triangles, this.sums, this.normals );
		const geometry = this.geometry;
		geometry.attributes.position.needsUpdate = true;
		geometry.attributes.normal.needsUpdate = true;
		geometry.computeBoundingSphere();
		const part = this.head.part( VELUM_PART );
		if ( part?.geometry !== geometry ) return;
		if ( this.head.cutaway ) part.outline.update( geometry );
		else part.outlineStale = true;

	}

	/** Register window.glasshead.velum; returns the function that removes it. */
	registerDebugField() {

		return registerDebug( 'velum', () => ( { opening: round3( this.opening ), nasalPortAreaMm2: round3( this.portArea ) } ) );

	}

}

function round3( value ) {

	return Math.round( value * 1000 ) / 1000;

}
