// The velum in the scene, posed by velum_opening (core/velum.js): the rest velum's mesh takes the
// blended positions, its normals and section follow, and window.glasshead.velum reports the
// opening and the nasal port's smallest cross-section. The normals blend the measured poses' own
// normals as the positions blend (renormalised: close to the posed mesh's, and far cheaper), and
// one bounding sphere holds all three poses, so every blend of two of them (a convex combination). The raised pose joins the cutaway's
// cavity (AirLayer.js), so that the port shows as air when the velum lowers. Nothing is
// allocated per frame.

import { BufferAttribute, BufferGeometry, Sphere, Vector3 } from 'three';
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
		this.triangles = Uint32Array.from( part.geometry.index.array );
		const sums = new Float64Array( 3 * rig.vertexCount );
		this.poseNormals = rig.poses.map( ( positions ) => vertexNormals( positions, this.triangles, sums, new Float32Array( 3 * rig.vertexCount ) ) );
		this.opening = NaN;
		this.portArea = 0;

		const geometry = new BufferGeometry();
		geometry.setAttribute( 'position', new BufferAttribute( this.positions, 3 ) );
		geometry.setAttribute( 'normal', new BufferAttribute( this.normals, 3 ) );
		geometry.setIndex( new BufferAttribute( this.triangles, 1 ) );
		geometry.boundingSphere = enclosingSphere( rig.poses );
		geometry.userData.midplaneTriangles = midplaneTriangles( rig.poses, this.triangles );
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
		// The segment poseVelum() blended: its first pose, and the share in rig.share[ 0 ].
		const first = opening <= this.rig.restShare ? 0 : 1;
		blendNormals( this.poseNormals[ first ], this.poseNormals[ first + 1 ], this.rig.share[ 0 ], this.normals );
		this.portArea = nasalPortArea( this.rig, opening );
		const geometry = this.geometry;
		geometry.attributes.position.needsUpdate = true;
		geometry.attributes.normal.needsUpdate = true;
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

/** Unit normals of a ( 1 - u ) + b u into target (a zero sum gives ( 0, 0, 0 )). */
export function blendNormals( a, b, u, target ) {

	for ( let i = 0; i < target.length; i += 3 ) {

		const x = a[ i ] * ( 1 - u ) + b[ i ] * u;
		const y = a[ i + 1 ] * ( 1 - u ) + b[ i + 1 ] * u;
		const z = a[ i + 2 ] * ( 1 - u ) + b[ i + 2 ] * u;
		const length = Math.sqrt( x * x + y * y + z * z );
		const scale = length > 0 ? 1 / length : 0;
		target[ i ] = x * scale;
		target[ i + 1 ] = y * scale;
		target[ i + 2 ] = z * scale;

	}

	return target;

}

/**
 * A sphere holding every vertex of every pose (xyz arrays), about the centre of their bounding
 * box, with a hair to spare for the float32 rounding of a blend.
 */
export function enclosingSphere( poses ) {

	const low = [ Infinity, Infinity, Infinity ];
	const high = [ - Infinity, - Infinity, - Infinity ];
	for ( const p of poses ) {

		for ( let i = 0; i < p.length; i ++ ) {

			low[ i % 3 ] = Math.min( low[ i % 3 ], p[ i ] );
			high[ i % 3 ] = Math.max( high[ i % 3 ], p[ i ] );

		}

	}

	const centre = new Vector3( ( low[ 0 ] + high[ 0 ] ) / 2, ( low[ 1 ] + high[ 1 ] ) / 2, ( low[ 2 ] + high[ 2 ] ) / 2 );
	let farthest = 0;
	for ( const p of poses ) {

		for ( let i = 0; i < p.length; i += 3 ) farthest = Math.max( farthest, ( p[ i ] - centre.x ) ** 2 + ( p[ i + 1 ] - centre.y ) ** 2 + ( p[ i + 2 ] - centre.z ) ** 2 );

	}

	return new Sphere( centre, Math.sqrt( farthest ) * ( 1 + 1e-6 ) + 1e-6 );

}

/**
 * The triangles (3 indices each) that may cross z = 0 in a blend of the poses. Corners at z >= 0
 * in every pose blend to z >= 0, and corners below -1e-6 mm in every pose blend to below 0 (the
 * hair keeps float32 rounding from reaching -0): such triangles never cross.
 */
export function midplaneTriangles( poses, triangles ) {

	const kept = [];
	for ( let t = 0; t < triangles.length; t += 3 ) {

		let below = false, near = false;
		for ( const p of poses ) {

			for ( let k = 0; k < 3; k ++ ) {

				const z = p[ 3 * triangles[ t + k ] + 2 ];
				below ||= z < 0;
				near ||= z > - 1e-6;

			}

		}

		if ( below && near ) kept.push( triangles[ t ], triangles[ t + 1 ], triangles[ t + 2 ] );

	}

	return Uint32Array.from( kept );

}

function round3( value ) {

	return Math.round( value * 1000 ) / 1000;

}
