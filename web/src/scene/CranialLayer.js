// The cranial cavity of the cutaway: the region of the cutting plane that the cranium's band
// encloses (core/cranialRegion.js), filled in the brain's colour, with the band's own section (the
// occipital bone) drawn over it in the bone's cut colour and its rims outlined. It lies flat on
// z = 0 in the cranium's group, so it moves and hides with the cranium. Reasons: docs/cutaway.md.

import {
	Box3,
	BufferAttribute,
	BufferGeometry,
	DoubleSide,
	LineBasicMaterial,
	LineLoop,
	Mesh,
	MeshBasicMaterial,
	ShapeUtils,
	Vector2,
	Vector3,
} from 'three';
import { cranialRegion } from '../core/cranialRegion.js';
import { insidePolygon } from '../core/sectionPolygon.js';
import { TISSUE_COLORS } from './materials.js';

/** Drawn width of the occipital bone's section, mm: the mesh is one sheet, so this is a stroke, not a measured thickness. */
export const BONE_STROKE_MM = 3;

/** Render orders: after the opaque anatomy (0), before the air (0.1 to 0.9) and the caps (from 1). */
const FILL_ORDER = 0.02;
const BONE_ORDER = 0.03;

/** The rims sit this far (mm) on the viewer's side of the plane, as the section outlines do. */
const RIM_LIFT_MM = 0.05;

function flatGeometry( points, triangles ) {

	const positions = new Float32Array( 3 * points.length / 2 );
	for ( let k = 0; k < points.length / 2; k ++ ) positions.set( [ points[ 2 * k ], points[ 2 * k + 1 ], 0 ], 3 * k );
	const geometry = new BufferGeometry();
	geometry.setAttribute( 'position', new BufferAttribute( positions, 3 ) );
	if ( triangles ) geometry.setIndex( triangles );
	return geometry;

}

/** Triangles filling the closed polygon `outline` (x y pairs). */
function fillGeometry( outline ) {

	const contour = Array.from( { length: outline.length / 2 }, ( _, k ) => new Vector2( outline[ 2 * k ], outline[ 2 * k + 1 ] ) );
	return flatGeometry( outline, ShapeUtils.triangulateShape( contour, [] ).flat() );

}

/**
 * A strip `width` mm wide along the open chain `line` (x y pairs), on the side of it where
 * `outline` lies, so that the stroke stays inside the region.
 */
export function strokeStrip( line, outline, width ) {

	const n = line.length / 2;
	const points = new Float64Array( 4 * n );
	const normal = ( k ) => {

		const a = Math.max( 0, k - 1 ), b = Math.min( n - 1, k + 1 );
		const dx = line[ 2 * b ] - line[ 2 * a ], dy = line[ 2 * b + 1 ] - line[ 2 * a + 1 ];
		const length = Math.hypot( dx, dy ) || 1;
		return [ - dy / length, dx / length ];

	};

	const middle = n >> 1;
	const [ mx, my ] = normal( middle );
	const side = insidePolygon( outline, line[ 2 * middle ] + mx * width / 2, line[ 2 * middle + 1 ] + my * width / 2 ) ? 1 : - 1;
	const triangles = [];
	for ( let k = 0; k < n; k ++ ) {

		const [ nx, ny ] = normal( k );
		points.set( [ line[ 2 * k ], line[ 2 * k + 1 ], line[ 2 * k ] + side * nx * width, line[ 2 * k + 1 ] + side * ny * width ], 4 * k );
		if ( k > 0 ) triangles.push( 2 * k - 2, 2 * k - 1, 2 * k, 2 * k - 1, 2 * k + 1, 2 * k );

	}

	return { points, triangles };

}

export class CranialLayer {

	/**
	 * @param {object} geometry the cranium's BufferGeometry (an open band; see core/cranialRegion.js)
	 * @returns a layer with `.region` null when the cranium bounds no region of the plane
	 */
	constructor( geometry ) {

		const positions = geometry.getAttribute( 'position' ).array;
		const index = geometry.index ? geometry.index.array : Uint32Array.from( { length: positions.length / 3 }, ( _, k ) => k );
		/** { outline, bone } on z = 0 (core/cranialRegion.js), or null. */
		this.region = cranialRegion( positions, index );
		this.meshes = [];
		if ( ! this.region ) return;

		const { outline, bone } = this.region;
		const fill = new Mesh( fillGeometry( outline ), new MeshBasicMaterial( { color: TISSUE_COLORS.brain, side: DoubleSide } ) );
		fill.name = 'cranial-cavity';
		fill.renderOrder = FILL_ORDER;
		this.meshes.push( fill );
		if ( bone.length >= 4 ) {

			const strip = strokeStrip( bone, outline, BONE_STROKE_MM );
			const mesh = new Mesh( flatGeometry( strip.points, strip.triangles ), new MeshBasicMaterial( { color: TISSUE_COLORS.boneCut, side: DoubleSide } ) );
			mesh.name = 'cranial-bone';
			mesh.renderOrder = BONE_ORDER;
			this.meshes.push( mesh );

		}

		const rim = new LineLoop( flatGeometry( outline ), new LineBasicMaterial( { color: TISSUE_COLORS.brainRim } ) );
		rim.name = 'cranial-rim';
		rim.position.z = - RIM_LIFT_MM;
		rim.renderOrder = BONE_ORDER;
		this.meshes.push( rim );
		for ( const mesh of this.meshes ) mesh.frustumCulled = false;
		this.setVisible( false );

	}

	/** Put the layer into `group` (the cranium's, so that it shares its motion and visibility). */
	attach( group ) {

		if ( this.meshes.length ) group.add( ...this.meshes );
		return this;

	}

	setVisible( on ) {

		this.visible = on;
		for ( const mesh of this.meshes ) mesh.visible = on;

	}

	/** A point of the cavity (the centroid of the fill's largest triangle), [x, y, 0], or null. */
	innerPoint() {

		const fill = this.meshes[ 0 ];
		if ( ! fill ) return null;
		const p = fill.geometry.getAttribute( 'position' ).array;
		const index = fill.geometry.index.array;
		let best = - 1, at = null;
		for ( let t = 0; t < index.length; t += 3 ) {

			const [ a, b, c ] = [ index[ t ], index[ t + 1 ], index[ t + 2 ] ].map( ( v ) => 3 * v );
			const area = Math.abs( ( p[ b ] - p[ a ] ) * ( p[ c + 1 ] - p[ a + 1 ] ) - ( p[ c ] - p[ a ] ) * ( p[ b + 1 ] - p[ a + 1 ] ) );
			if ( area > best ) {

				best = area;
				at = [ ( p[ a ] + p[ b ] + p[ c ] ) / 3, ( p[ a + 1 ] + p[ b + 1 ] + p[ c + 1 ] ) / 3, 0 ];

			}

		}

		return at;

	}

	/**
	 * What window.glasshead.cranialProbe reports: a point of the cavity (innerPoint), where it is
	 * on the canvas (CSS pixels, from `viewer.screenRect`) and the colours to expect there.
	 */
	probe( viewer ) {

		const point = this.innerPoint();
		if ( ! point ) return null;
		const at = new Vector3().fromArray( point ).applyMatrix4( this.meshes[ 0 ].matrixWorld );
		const rect = viewer.screenRect( new Box3( at, at ) );
		return { point, x: rect?.x ?? null, y: rect?.y ?? null, visible: this.visible, brainColor: TISSUE_COLORS.brain, tissueColor: TISSUE_COLORS.skinCut, boneColor: TISSUE_COLORS.bone };

	}

	dispose() {

		for ( const mesh of this.meshes ) {

			mesh.removeFromParent();
			mesh.geometry.dispose();
			mesh.material.dispose();

		}

		this.meshes = [];

	}

}
