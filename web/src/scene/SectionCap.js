// A flat cap over the cut face of a closed mesh, lying on the cutting plane itself.
//
// The section shading of materials.js draws a clipped mesh's inside faces in the cut colour; they lie
// on the far side of the mesh, so anything reaching into the solid behind the cut shows through them
// (the teeth pressed into the sides of the tongue). The cap is drawn where the stencil buffer says the
// plane is inside the mesh, as in three.js's clipping-stencil example: the mesh's back faces add one
// and its front faces take one away along each pixel's ray (both clipped by the plane, with no depth
// test), so a pixel whose ray meets the plane inside the solid is left at 1. The cap then writes the
// plane's own depth there and sets the stencil back to 0 for the next cap.

import {
	AlwaysStencilFunc,
	BackSide,
	DecrementWrapStencilOp,
	DoubleSide,
	FrontSide,
	IncrementWrapStencilOp,
	Mesh,
	MeshBasicMaterial,
	NotEqualStencilFunc,
	PlaneGeometry,
	Quaternion,
	ReplaceStencilOp,
	Vector3,
} from 'three';

/** Side of the square cap, mm: it covers any cut through the head. */
export const CAP_SIZE_MM = 1000;

const PLANE_GEOMETRY_NORMAL = new Vector3( 0, 0, 1 );
const scratchNormal = new Vector3();
const scratchPoint = new Vector3();
const scratchRotation = new Quaternion();
const scratchScale = new Vector3( CAP_SIZE_MM, CAP_SIZE_MM, 1 );

function stencilCounter( side, op, plane ) {

	return new MeshBasicMaterial( {
		side,
		colorWrite: false,
		depthWrite: false,
		depthTest: false,
		clippingPlanes: [ plane ],
		stencilWrite: true,
		stencilFunc: AlwaysStencilFunc,
		stencilFail: op,
		stencilZFail: op,
		stencilZPass: op,
	} );

}

export class SectionCap {

	/**
	 * geometry: the closed mesh's BufferGeometry (shared, so deformations follow); plane: the cutting
	 * Plane (the part keeps dot( n, p ) + constant >= 0); color: the cut colour; renderOrder: where the
	 * counting and the cap come among the other caps (each cap needs its own, after opaque anatomy).
	 */
	constructor( geometry, plane, color, renderOrder ) {

		this.plane = plane;
		this.counters = [
			new Mesh( geometry, stencilCounter( BackSide, IncrementWrapStencilOp, plane ) ),
			new Mesh( geometry, stencilCounter( FrontSide, DecrementWrapStencilOp, plane ) ),
		];
		this.cap = new Mesh( new PlaneGeometry( 1, 1 ), new MeshBasicMaterial( {
			color,
			side: DoubleSide,
			stencilWrite: true,
			stencilRef: 0,
			stencilFunc: NotEqualStencilFunc,
			stencilFail: ReplaceStencilOp,
			stencilZFail: ReplaceStencilOp,
			stencilZPass: ReplaceStencilOp,
		} ) );
		this.cap.name = 'section-cap';
		this.cap.frustumCulled = false;
		// The cap lies on the plane whatever frame its parent moves in.
		this.cap.onBeforeRender = () => this.alignWithCut();
		for ( const counter of this.counters ) {

			counter.name = 'section-cap-stencil';
			counter.renderOrder = renderOrder;

		}

		this.cap.renderOrder = renderOrder + 0.5;
		this.setVisible( false );

	}

	/** The meshes to add beside the clipped mesh (in its group, so they share its motion and visibility). */
	get meshes() {

		return [ ...this.counters, this.cap ];

	}

	setVisible( on ) {

		for ( const mesh of this.meshes ) mesh.visible = on;

	}

	/** Follow a replaced geometry of the clipped mesh. */
	setGeometry( geometry ) {

		for ( const counter of this.counters ) counter.geometry = geometry;

	}

	/** Put the cap square on the plane, centred on the plane's point nearest the origin. */
	alignWithCut() {

		scratchNormal.copy( this.plane.normal ).normalize();
		this.plane.coplanarPoint( scratchPoint );
		scratchRotation.setFromUnitVectors( PLANE_GEOMETRY_NORMAL, scratchNormal );
		this.cap.matrixWorld.compose( scratchPoint, scratchRotation, scratchScale );

	}

	dispose() {

		for ( const counter of this.counters ) counter.material.dispose();
		this.cap.geometry.dispose();
		this.cap.material.dispose();

	}

}
