// Eyes and nostrils: the face skin has openings there, which would let the viewer look straight
// into the hollow head. Each is closed by a patch: the eyes by a shallow dome of sclera (shadowed
// under the lids) with an eyeball and an upper lid in front of it (Eyes.js), the nostrils by a
// dark dimple.
//
// Which opening is which: openings crossing the mid-sagittal plane (the mouth slit, a neck rim) and
// the largest one (the rim of the face mask) are left open; of the rest, the two highest that lie
// on opposite sides of the midline are the eyes, and the others are nostrils.

import { BufferAttribute, BufferGeometry, Color, DoubleSide, Mesh, MeshStandardMaterial } from 'three';
import { boundaryLoops, domePatch, loopFrame } from '../core/openings.js';
import { addSectionShading, createColorPatchedMaterial, TISSUE_COLORS } from './materials.js';
import { EYE_COLORS } from './eyeMaterials.js';
import { buildEyeMeshes } from './Eyes.js';

/** Eye proportions, in mm and as fractions of the opening's mean radius. */
export const EYE = Object.freeze( {
	bulge: 0.12, // of the opening's radius: the dome behind the eyeball, seen in the corners
	sclera: EYE_COLORS.sclera,
	lidShadow: '#7b5a50',
} );

/**
 * Find the openings of a skin geometry to close. Returns [{ loop, frame, kind: 'eye'|'nostril' }].
 */
export function classifyOpenings( positions, index ) {

	const loops = boundaryLoops( index ).filter( ( loop ) => loop.length >= 3 ).map( ( loop ) => ( { loop, frame: loopFrame( positions, loop ) } ) );
	if ( loops.length === 0 ) return [];
	const largest = loops.reduce( ( a, b ) => ( b.frame.perimeter > a.frame.perimeter ? b : a ) );
	const closable = loops.filter( ( o ) => o !== largest && ( o.frame.minZ > 0 || o.frame.maxZ < 0 ) );
	closable.sort( ( a, b ) => b.frame.centre[ 1 ] - a.frame.centre[ 1 ] );

	const eyes = [];
	for ( const candidate of closable ) {

		if ( eyes.length === 2 ) break;
		if ( eyes.length === 0 || Math.sign( eyes[ 0 ].frame.centre[ 2 ] ) !== Math.sign( candidate.frame.centre[ 2 ] ) ) eyes.push( candidate );

	}

	return closable.map( ( o ) => ( { ...o, kind: eyes.includes( o ) && eyes.length === 2 ? 'eye' : 'nostril' } ) );

}

/**
 * Normals of a sphere behind the opening (its centre 1.3 mean radii back along the normal), so the
 * eye is shaded like a ball even where the opening's rim is uneven.
 */
function eyeballNormals( positions, frame ) {

	const { centre, normal, meanRadius } = frame;
	const depth = 1.3 * meanRadius;
	const ball = centre.map( ( c, k ) => c - normal[ k ] * depth );
	const normals = new Float32Array( positions.length );
	for ( let i = 0; i < positions.length; i += 3 ) {

		const d = [ positions[ i ] - ball[ 0 ], positions[ i + 1 ] - ball[ 1 ], positions[ i + 2 ] - ball[ 2 ] ];
		const length = Math.hypot( ...d ) || 1;
		for ( let k = 0; k < 3; k ++ ) normals[ i + k ] = d[ k ] / length;

	}

	return normals;

}

/** Material that paints the eye dome from its per-vertex `eyeCoord` (u, v in mm; s out to the lid). */
function createEyeMaterial() {

	return createColorPatchedMaterial( { color: '#ffffff', roughness: 0.25, side: DoubleSide }, { sectionColor: TISSUE_COLORS.skinCut }, {
		key: 'glasshead-eye',
		attributes: 'attribute vec3 eyeCoord;',
		varyings: 'varying vec3 vEyeCoord;',
		vertex: 'vEyeCoord = eyeCoord;',
		uniforms: { uSclera: { value: new Color( EYE.sclera ) }, uLid: { value: new Color( EYE.lidShadow ) } },
		declarations: 'uniform vec3 uSclera, uLid;',
		color: `	// The lids shade the eye's rim.
	vec3 eye = mix( uSclera * 0.85, uLid, smoothstep( 0.65, 1.0, vEyeCoord.z ) * 0.85 );
	diffuseColor.rgb *= eye;`,
	} );

}

function createNostrilMaterial() {

	return addSectionShading( new MeshStandardMaterial( { color: TISSUE_COLORS.skinCavity, roughness: 0.9, side: DoubleSide } ), { sectionColor: TISSUE_COLORS.skinCut } );

}

/**
 * Meshes closing the openings of a skin geometry (indexed, positions in mm). Each mesh has
 * userData.opening = 'eye' | 'nostril'. Returns [] when the geometry has no closable openings.
 */
export function buildOpeningMeshes( geometry ) {

	if ( ! geometry.index ) return [];
	const positions = geometry.getAttribute( 'position' ).array;
	const openings = classifyOpenings( positions, geometry.index.array );
	const materials = { eye: null, nostril: null, eyeball: null, lid: null };
	return openings.flatMap( ( { loop, frame, kind } ) => {

		const bulge = kind === 'eye' ? EYE.bulge * frame.meanRadius : - 0.6 * frame.meanRadius;
		const patch = domePatch( positions, loop, frame, { rings: kind === 'eye' ? 10 : 4, bulge } );
		const patchGeometry = new BufferGeometry();
		patchGeometry.setAttribute( 'position', new BufferAttribute( patch.positions, 3 ) );
		patchGeometry.setAttribute( 'eyeCoord', new BufferAttribute( patch.coords, 3 ) );
		patchGeometry.setIndex( new BufferAttribute( patch.index, 1 ) );
		if ( kind === 'eye' ) patchGeometry.setAttribute( 'normal', new BufferAttribute( eyeballNormals( patch.positions, frame ), 3 ) );
		else patchGeometry.computeVertexNormals();
		materials[ kind ] ??= kind === 'eye' ? createEyeMaterial() : createNostrilMaterial();
		const mesh = new Mesh( patchGeometry, materials[ kind ] );
		mesh.name = kind;
		mesh.userData.opening = kind;
		return kind === 'eye' ? [ mesh, ...buildEyeMeshes( positions, loop, frame, bulge, materials ) ] : [ mesh ];

	} );

}
