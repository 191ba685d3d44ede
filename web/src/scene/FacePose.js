// The face in the scene. With a face rig, every frame the articulation changes, the skin, the lips
// and the head shell are posed by the real-time face rig (web/src/core/faceRig.js) straight into
// their geometries' position arrays; their normals and bounding spheres are redone where the rig
// can move vertices (core/movingMesh.js) and the normals welded again across the seam where the
// face skin meets the head shell. Nothing is allocated per pose. Without one, the
// lower lip rides rigidly on the jaw and the lip gap is measured here (midlineLips, lipGap).

import { createFaceRig, GAP_LIPS, poseFace, restFaceRig } from '../core/faceRig.js';
import { vertexNormals } from '../core/meshVolume.js';
import { enclose, movingMesh, updateNormals } from '../core/movingMesh.js';

/** Skin vertices closer than this (mm) are one point of the seam (as the head welds it at load). */
const SEAM_TOLERANCE_MM = 0.01;

export class FacePose {

	/**
	 * @param {object} definition the face rig (GET /face/rig)
	 * @param {import('./Head.js').Head} head with every mesh of the definition loaded, at rest
	 * @param {import('../core/paramState.js').ParamState} state holding the lip parameters
	 * Throws when a mesh is missing or is not the one the rig was built for.
	 */
	constructor( definition, head, state ) {

		this.head = head;
		// The definition names the meshes it poses and the lip parameters, in its own order.
		this.parts = Object.keys( definition.meshes ?? {} ).map( ( name ) => {

			const part = head.part( name );
			if ( ! part ) throw new Error( `the face rig needs the mesh "${ name }", which is not loaded` );
			return part;

		} );
		const rest = Object.fromEntries( this.parts.map( ( part ) => [ part.name, Float32Array.from( part.geometry.attributes.position.array ) ] ) );
		this.rig = createFaceRig( definition, rest );
		this.out = Object.fromEntries( this.parts.map( ( part ) => [ part.name, part.geometry.attributes.position.array ] ) );
		restFaceRig( this.rig, this.out );
		const lipNames = definition.parameters.map( ( p ) => p.name );
		this.lipIndex = Int32Array.from( lipNames, ( name ) => state.indexOf( name ) );
		this.lipValues = new Float64Array( lipNames.length );
		/** The inputs of the last pose (lip values, then the jaw pose): the same again is a no-op. */
		this.last = new Float64Array( lipNames.length + 12 ).fill( NaN );
		const skins = this.parts.filter( ( part ) => part.tissue === 'skin' );
		const seam = seamGroups( skins );
		this.meshes = this.parts.map( ( part ) => {

			const geometry = part.geometry;
			const positions = geometry.attributes.position.array;
			const normals = geometry.attributes.normal.array;
			const count = geometry.attributes.position.count;
			const index = geometry.index ? geometry.index.array : Uint32Array.from( { length: count }, ( _, k ) => k );
			// The rest normals once; poses redo those around the moving vertices and the seam's.
			vertexNormals( positions, index, new Float64Array( 3 * count ), normals );
			const skin = skins.indexOf( part );
			const onSeam = Array.from( seam.members ).filter( ( _, k ) => k % 2 === 1 && seam.members[ k - 1 ] === skin );
			geometry.computeBoundingSphere(); // its Sphere, reset by every pose
			return { part, moving: movingMesh( positions, index, this.rig.meshes[ part.name ].moving, skin < 0 ? [] : onSeam ) };

		} );
		this.seam = seam;
		weldSeam( seam );

	}

	/**
	 * Pose the face for the parameter values (the state's array) and the jaw pose (row-major
	 * 3 x 4, jaw.js). Returns the lips' mid-sagittal gap, mm.
	 */
	pose( values, jawPose ) {

		for ( let k = 0; k < this.lipIndex.length; k ++ ) this.lipValues[ k ] = values[ this.lipIndex[ k ] ];
		// Tongue and velum sliders leave the face as it was: nothing to redo.
		if ( this.unchanged( jawPose ) ) return this.rig.gaps[ GAP_LIPS ];
		poseFace( this.rig, this.lipValues, jawPose, this.out );
		for ( let m = 0; m < this.meshes.length; m ++ ) {

			const { part, moving } = this.meshes[ m ];
			const geometry = part.geometry;
			updateNormals( moving, geometry.attributes.position.array, geometry.attributes.normal.array );
			enclose( moving, geometry.attributes.position.array, geometry.boundingSphere );
			geometry.attributes.position.needsUpdate = true;
			geometry.attributes.normal.needsUpdate = true;
			// As Head.updateVertices: the section outline follows now if it shows, else when it does.
			if ( this.head.cutaway ) part.outline.update( geometry );
			else part.outlineStale = true;

		}

		weldSeam( this.seam );
		return this.rig.gaps[ GAP_LIPS ];

	}

	/** Whether the lip values and the jaw pose are those of the last pose (and remember them). */
	unchanged( jawPose ) {

		const { last, lipValues } = this;
		let same = true;
		for ( let k = 0; k < lipValues.length; k ++ ) {

			same = same && last[ k ] === lipValues[ k ];
			last[ k ] = lipValues[ k ];

		}

		for ( let k = 0; k < 12; k ++ ) {

			same = same && last[ lipValues.length + k ] === jawPose[ k ];
			last[ lipValues.length + k ] = jawPose[ k ];

		}

		return same;

	}

}

/**
 * The vertices the skin meshes share along their seam, found once: groups of ( normals array,
 * vertex ) at one position, as flat lists. Returns { normals: Float32Array[], members: Int32Array
 * (mesh, vertex pairs), starts: Int32Array (group offsets into members, plus the end) }.
 */
export function seamGroups( parts ) {

	const normals = parts.map( ( part ) => part.geometry.attributes.normal.array );
	const byPoint = new Map();
	parts.forEach( ( part, m ) => {

		const p = part.geometry.attributes.position.array;
		for ( let v = 0; v < p.length / 3; v ++ ) {

			const key = `${ Math.round( p[ 3 * v ] / SEAM_TOLERANCE_MM ) },${ Math.round( p[ 3 * v + 1 ] / SEAM_TOLERANCE_MM ) },${ Math.round( p[ 3 * v + 2 ] / SEAM_TOLERANCE_MM ) }`;
			if ( ! byPoint.has( key ) ) byPoint.set( key, [] );
			byPoint.get( key ).push( m, v );

		}

	} );
	const members = [];
	const starts = [ 0 ];
	for ( const group of byPoint.values() ) {

		const meshes = new Set( group.filter( ( _, k ) => k % 2 === 0 ) );
		if ( meshes.size < 2 ) continue;
		members.push( ...group );
		starts.push( members.length / 2 );

	}

	return { normals, members: Int32Array.from( members ), starts: Int32Array.from( starts ) };

}

/** Give every vertex of a seam group the normalised sum of the group's normals. */
export function weldSeam( { normals, members, starts } ) {

	for ( let g = 0; g + 1 < starts.length; g ++ ) {

		let x = 0, y = 0, z = 0;
		for ( let k = starts[ g ]; k < starts[ g + 1 ]; k ++ ) {

			const n = normals[ members[ 2 * k ] ];
			const o = 3 * members[ 2 * k + 1 ];
			x += n[ o ]; y += n[ o + 1 ]; z += n[ o + 2 ];

		}

		const length = Math.sqrt( x * x + y * y + z * z );
		if ( length === 0 ) continue;
		for ( let k = starts[ g ]; k < starts[ g + 1 ]; k ++ ) {

			const n = normals[ members[ 2 * k ] ];
			const o = 3 * members[ 2 * k + 1 ];
			n[ o ] = x / length; n[ o + 1 ] = y / length; n[ o + 2 ] = z / length;

		}

	}

}

/**
 * The mid-sagittal crossings of the lips at rest: for each edge of a lip mesh with one end at
 * z <= 0 and the other at z > 0, the point where it crosses z = 0 (Float64Array, x y per point).
 * The jaw turns about a z-parallel axis, so a posed crossing is the posed rest crossing.
 * Returns { upper, lower } or null when a lip is missing.
 */
export function midlineLips( head ) {

	const upper = head.part( 'upper_lip' );
	const lower = head.part( 'lower_lip' );
	if ( ! upper || ! lower ) return null;
	return { upper: midlineCrossings( upper.geometry ), lower: midlineCrossings( lower.geometry ) };

}

/** Crossings of the plane z = 0 by the edges of a geometry's triangles (x y per crossing). */
export function midlineCrossings( geometry ) {

	const positions = geometry.getAttribute( 'position' );
	const index = geometry.index;
	const corner = ( t, k ) => ( index ? index.getX( 3 * t + k ) : 3 * t + k );
	const triangles = index ? index.count / 3 : positions.count / 3;
	const seen = new Set();
	const points = [];
	for ( let t = 0; t < triangles; t ++ ) {

		for ( let k = 0; k < 3; k ++ ) {

			let a = corner( t, k );
			let b = corner( t, ( k + 1 ) % 3 );
			if ( positions.getZ( a ) > 0 ) [ a, b ] = [ b, a ];
			if ( ! ( positions.getZ( a ) <= 0 && positions.getZ( b ) > 0 ) ) continue;
			const key = a * 4294967296 + b;
			if ( seen.has( key ) ) continue;
			seen.add( key );
			const za = positions.getZ( a );
			const s = za / ( za - positions.getZ( b ) );
			points.push( positions.getX( a ) + s * ( positions.getX( b ) - positions.getX( a ) ) );
			points.push( positions.getY( a ) + s * ( positions.getY( b ) - positions.getY( a ) ) );

		}

	}

	return Float64Array.from( points );

}

/**
 * The lips' mid-sagittal gap, mm: the lowest midline point of the upper lip above the highest of
 * the lower lip, which rides on the jaw (pose from jawPose()); 0 when they touch.
 */
export function lipGap( lips, pose ) {

	let upperLowest = Infinity;
	for ( let k = 1; k < lips.upper.length; k += 2 ) upperLowest = Math.min( upperLowest, lips.upper[ k ] );
	let lowerHighest = - Infinity;
	const lower = lips.lower;
	for ( let k = 0; k < lower.length; k += 2 ) {

		lowerHighest = Math.max( lowerHighest, pose[ 4 ] * lower[ k ] + pose[ 5 ] * lower[ k + 1 ] + pose[ 7 ] );

	}

	return Math.max( 0, upperLowest - lowerHighest );

}
