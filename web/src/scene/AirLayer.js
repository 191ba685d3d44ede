// The air of the cutaway: a light, translucent layer on the cutting plane wherever the vocal
// tract is empty at this frame. Method and reasons: docs/cutaway.md.
//
// The cavity is a union of pieces, each marked in the stencil buffer's high bit (AIR_BIT):
//   - the airway's own mid-sagittal polygon (core/sectionPolygon.js; it is open, so its section
//     is joined and closed on the CPU once, then drawn flat on the plane);
//   - the same polygon's oral part riding on the jaw (the mouth opens with it);
//   - the rest tongue, where it stood when the airway was measured, and the rest tongue riding on
//     the jaw (when the tongue drops or the jaw opens, air appears where it was);
//   - the velum's rest and raised poses (when it lowers, the port behind it opens).
// Closed pieces are counted in the low bits as SectionCap.js does (back faces add one, front
// faces take one away, clipped by the plane) and a plane quad turns a non-zero count into
// AIR_BIT. The mandible then erases the bit where the plane is inside it (its own section shows).
// Last, one plane quad draws the air colour where the bit is set and clears the stencil, before
// the tongue, lips, velum and bone caps (render orders from 1) draw over it.

import {
	AlwaysStencilFunc,
	BackSide,
	Box3,
	BufferAttribute,
	BufferGeometry,
	CustomBlending,
	DecrementWrapStencilOp,
	DoubleSide,
	EqualStencilFunc,
	FrontSide,
	IncrementWrapStencilOp,
	Mesh,
	MeshBasicMaterial,
	NotEqualStencilFunc,
	OneMinusSrcAlphaFactor,
	PlaneGeometry,
	Quaternion,
	ReplaceStencilOp,
	ShapeUtils,
	SrcAlphaFactor,
	Vector2,
	Vector3,
	ZeroStencilOp,
} from 'three';
import { airwayPolygon, chainSegments, crossingsAt } from '../core/sectionPolygon.js';
import { planeSectionSegments } from '../core/section.js';
import { TISSUE_COLORS } from './materials.js';

/** Stencil bit of "air here"; the low bits count a closed piece's crossings. */
export const AIR_BIT = 0x80;
const COUNT_MASK = 0x7f;

/** Opacity of the air layer: the left half's palate, teeth and electrodes stay visible through it. */
export const AIR_OPACITY = 0.85;

/** Triangles of the airway polygon in front of this x (mm) ride on the jaw too (the mouth). */
export const ORAL_BACK_X_MM = - 25;

/** Render orders: after the opaque anatomy (0), before the first section cap (1). */
const FIRST_ORDER = 0.1;
const AIR_ORDER = 0.9;

const QUAD_SIZE_MM = 1000;
const QUAD_NORMAL = new Vector3( 0, 0, 1 );
const scratchNormal = new Vector3();
const scratchPoint = new Vector3();
const scratchRotation = new Quaternion();
const scratchScale = new Vector3( QUAD_SIZE_MM, QUAD_SIZE_MM, 1 );

/** Stencil-only material: writes no colour and no depth, tests no depth. */
function stencilMaterial( options ) {

	return new MeshBasicMaterial( { colorWrite: false, depthWrite: false, depthTest: false, stencilWrite: true, ...options } );

}

function counter( geometry, side, op, plane, order ) {

	const mesh = new Mesh( geometry, stencilMaterial( {
		side, clippingPlanes: [ plane ], stencilFunc: AlwaysStencilFunc, stencilWriteMask: COUNT_MASK,
		stencilFail: op, stencilZFail: op, stencilZPass: op,
	} ) );
	mesh.name = 'air-stencil';
	mesh.renderOrder = order;
	mesh.frustumCulled = false;
	return mesh;

}

/** A square on the cutting plane, whatever frame its parent moves in. */
function planeQuad( plane, material, order, name ) {

	const mesh = new Mesh( new PlaneGeometry( 1, 1 ), material );
	mesh.name = name;
	mesh.renderOrder = order;
	mesh.frustumCulled = false;
	mesh.onBeforeRender = () => {

		scratchNormal.copy( plane.normal ).normalize();
		plane.coplanarPoint( scratchPoint );
		scratchRotation.setFromUnitVectors( QUAD_NORMAL, scratchNormal );
		mesh.matrixWorld.compose( scratchPoint, scratchRotation, scratchScale );

	};

	return mesh;

}

/** A flat BufferGeometry on z = 0 filling `outline` less `holes` (x y pairs), keeping triangles `keep( cx, cy )`. */
function polygonGeometry( outline, holes, keep = () => true ) {

	const toVectors = ( points ) => Array.from( { length: points.length / 2 }, ( _, k ) => new Vector2( points[ 2 * k ], points[ 2 * k + 1 ] ) );
	const contour = toVectors( outline );
	const holeVectors = holes.map( toVectors );
	const all = [ contour, ...holeVectors ].flat();
	const triangles = ShapeUtils.triangulateShape( contour, holeVectors ).filter( ( [ a, b, c ] ) => keep( ( all[ a ].x + all[ b ].x + all[ c ].x ) / 3, ( all[ a ].y + all[ b ].y + all[ c ].y ) / 3 ) );
	const positions = new Float32Array( 3 * all.length );
	all.forEach( ( v, k ) => positions.set( [ v.x, v.y, 0 ], 3 * k ) );
	const geometry = new BufferGeometry();
	geometry.setAttribute( 'position', new BufferAttribute( positions, 3 ) );
	geometry.setIndex( triangles.flat() );
	return geometry;

}

export class AirLayer {

	/**
	 * @param {{ airway: object, plane: object, tongue?: object|null, velum?: object|null,
	 *   jaw?: object|null, eraser?: object|null }} parts the airway's BufferGeometry; the cutting
	 *   Plane; the rest tongue's and rest velum's geometries (copied: they are the cavity where
	 *   those stood, whatever the scene's meshes do later); the Group that carries the jaw; the
	 *   mandible's geometry, whose section erases the air
	 */
	constructor( { airway, plane, tongue = null, velum = null, jaw = null, eraser = null } ) {

		this.plane = plane;
		this.objects = [];
		this.jawObjects = [];
		this.order = FIRST_ORDER;
		const positions = airway.getAttribute( 'position' ).array;
		const index = airway.index ? airway.index.array : null;
		const segments = new Float32Array( 6 * ( index ? index.length / 3 : positions.length / 9 ) );
		const count = planeSectionSegments( positions, index, 0, segments );
		/** The airway's mid-sagittal polygon (core/sectionPolygon.js airwayPolygon). */
		this.polygon = airwayPolygon( chainSegments( segments, count ) );

		const { outline, holes } = this.polygon;
		this.addFlat( polygonGeometry( outline, holes ), this.objects );
		if ( jaw ) this.addFlat( polygonGeometry( outline, holes, ( x ) => x > ORAL_BACK_X_MM ), this.jawObjects );
		this.restTongue = tongue ? tongue.clone() : null;
		if ( this.restTongue ) {

			this.addClosed( this.restTongue, this.objects );
			if ( jaw ) this.addClosed( this.restTongue, this.jawObjects );

		}

		this.velumPieces = [];
		if ( velum ) this.addVelumPose( velum.getAttribute( 'position' ).array, velum.index );
		this.eraser = eraser;
		this.jaw = jaw;
		this.build();

	}

	/** Add a pose of the velum (positions in its vertex order, e.g. the raised pose) to the cavity. */
	addVelumPose( positions, index ) {

		const geometry = new BufferGeometry();
		geometry.setAttribute( 'position', new BufferAttribute( Float32Array.from( positions ), 3 ) );
		geometry.setIndex( index.clone() );
		this.addClosed( geometry, this.objects );
		this.velumPieces.push( geometry );
		if ( this.built ) this.build();

	}

	nextOrder() {

		this.order += 0.01;
		return this.order;

	}

	addFlat( geometry, list ) {

		const mesh = new Mesh( geometry, stencilMaterial( { side: DoubleSide, stencilFunc: AlwaysStencilFunc, stencilRef: AIR_BIT, stencilZPass: ReplaceStencilOp } ) );
		mesh.name = 'air-polygon';
		mesh.frustumCulled = false;
		list.push( { kind: 'flat', mesh } );

	}

	addClosed( geometry, list ) {

		list.push( { kind: 'closed', geometry } );

	}

	/** (Re)build the ordered stencil passes: pieces, jaw-borne pieces, the eraser, the air quad. */
	build() {

		this.dispose();
		this.built = true;
		this.order = FIRST_ORDER;
		this.meshes = [];
		this.jawMeshes = [];
		const place = ( pieces, target ) => {

			for ( const piece of pieces ) {

				if ( piece.kind === 'flat' ) {

					piece.mesh.renderOrder = this.nextOrder();
					target.push( piece.mesh );
					continue;

				}

				const order = this.nextOrder();
				target.push( counter( piece.geometry, BackSide, IncrementWrapStencilOp, this.plane, order ), counter( piece.geometry, FrontSide, DecrementWrapStencilOp, this.plane, order ) );
				// A non-zero count becomes the air bit.
				target.push( planeQuad( this.plane, stencilMaterial( { side: DoubleSide, stencilFunc: NotEqualStencilFunc, stencilRef: AIR_BIT, stencilFuncMask: COUNT_MASK, stencilZPass: ReplaceStencilOp } ), this.nextOrder(), 'air-mark' ) );

			}

		};

		place( this.objects, this.meshes );
		place( this.jawObjects, this.jawMeshes );
		if ( this.eraser ) {

			const order = this.nextOrder();
			this.jawMeshes.push( counter( this.eraser, BackSide, IncrementWrapStencilOp, this.plane, order ), counter( this.eraser, FrontSide, DecrementWrapStencilOp, this.plane, order ) );
			this.meshes.push( planeQuad( this.plane, stencilMaterial( { side: DoubleSide, stencilFunc: NotEqualStencilFunc, stencilRef: 0, stencilFuncMask: COUNT_MASK, stencilZPass: ZeroStencilOp } ), this.nextOrder(), 'air-erase' ) );

		}

		// Not `transparent` (it must stay in the opaque queue, before the caps), but blended.
		this.quad = planeQuad( this.plane, new MeshBasicMaterial( {
			color: TISSUE_COLORS.air, opacity: AIR_OPACITY, side: DoubleSide,
			blending: CustomBlending, blendSrc: SrcAlphaFactor, blendDst: OneMinusSrcAlphaFactor,
			stencilWrite: true, stencilFunc: EqualStencilFunc, stencilRef: AIR_BIT, stencilFuncMask: AIR_BIT,
			stencilZPass: ZeroStencilOp, stencilZFail: ZeroStencilOp,
		} ), AIR_ORDER, 'air' );
		this.meshes.push( this.quad );
		this.group?.add( ...this.meshes );
		this.jaw?.add( ...this.jawMeshes );
		this.setVisible( this.visible ?? false );

	}

	/** Put the layer into `group` (the head's), the jaw-borne passes into the jaw's group. */
	attach( group ) {

		this.group = group;
		group.add( ...this.meshes );
		this.jaw?.add( ...this.jawMeshes );
		return this;

	}

	setVisible( on ) {

		this.visible = on;
		for ( const mesh of [ ...this.meshes, ...this.jawMeshes ] ) mesh.visible = on;

	}

	/**
	 * A point of the oral air between the tongue dorsum and the palate: on the airway polygon's
	 * walls at x (default: the rest tongue's highest point), halfway between them. [x, y, 0] or null.
	 */
	oralPoint( x = this.tongueTopX() ) {

		const upper = new Float64Array( 8 ), lower = new Float64Array( 8 );
		const nu = crossingsAt( this.polygon.upper, x, upper );
		const nl = crossingsAt( this.polygon.lower, x, lower );
		if ( nu === 0 || nl === 0 ) return null;
		return [ x, ( upper[ nu - 1 ] + lower[ nl - 1 ] ) / 2, 0 ];

	}

	/**
	 * What window.glasshead.airProbe reports: the oral air point (oralPoint), where it is on the
	 * canvas (CSS pixels, from `viewer.screenRect`) and the colours to expect there.
	 */
	probe( viewer ) {

		const point = this.oralPoint();
		if ( ! point ) return null;
		const at = new Vector3().fromArray( point );
		const rect = viewer.screenRect( new Box3( at, at ) );
		return { point, x: rect?.x ?? null, y: rect?.y ?? null, visible: this.visible, airColor: TISSUE_COLORS.air, airOpacity: AIR_OPACITY, tissueColor: TISSUE_COLORS.skinCut };

	}

	tongueTopX() {

		const p = this.restTongue?.getAttribute( 'position' ).array;
		if ( ! p ) return - 10;
		let top = 0;
		for ( let v = 0; v < p.length / 3; v ++ ) if ( p[ 3 * v + 1 ] > p[ 3 * top + 1 ] ) top = v;
		return p[ 3 * top ];

	}

	/** Remove the passes from the scene and free their materials (the pieces' geometries stay). */
	dispose() {

		for ( const mesh of [ ...( this.meshes ?? [] ), ...( this.jawMeshes ?? [] ) ] ) {

			mesh.removeFromParent();
			mesh.material.dispose();
			if ( mesh.name === 'air-mark' || mesh.name === 'air-erase' || mesh.name === 'air' ) mesh.geometry.dispose();

		}

		this.meshes = [];
		this.jawMeshes = [];

	}

}
