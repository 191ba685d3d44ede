// The EPG electrodes on the 3D palate: a dot for each electrode, a square for each contacted one
// (Cohen, Beskow and Massaro 1998, Figures 7 and 8). Two instanced meshes hold them; each frame
// the contacted electrodes' matrices go to the squares and the others' to the dots, from matrices
// built once, so nothing is allocated.
//
// A contacted electrode lies between the palate and the tongue that touches it, so it is hidden
// in any view from outside. While the skin is see-through or cut away, a faint second pass without
// depth test shows the markers through the tongue; the cutaway's clipping plane applies to both
// passes. The faint pass blends but stays in the opaque queue, after the anatomy and before the
// lips and the skin, so that whatever of them is opaque covers it (the nostril with the cutaway on,
// the upper lip) and whatever is faded blends over it.

import {
	Box3,
	BoxGeometry,
	CustomBlending,
	Group,
	InstancedMesh,
	Matrix4,
	MeshBasicMaterial,
	MeshStandardMaterial,
	SphereGeometry,
	Vector3,
} from 'three';

export const ELECTRODE_COLORS = Object.freeze( { dot: '#4a5562', square: '#10161d' } );
/** mm: dot radius, square side and thickness, and the lift off the palate toward the tongue. */
export const ELECTRODE_SIZES = Object.freeze( { dot: 0.55, square: 1.9, thickness: 0.35, lift: 0.2 } );
/** Opacity of the see-through pass. */
const GHOST_OPACITY = 0.45;
/**
 * The see-through pass: after the opaque anatomy (0) and the section caps and outlines (1 to 7),
 * before the lips (LIP_RENDER_ORDER, 9) and the skin passes (SKIN_RENDER_ORDER, 10 to 12).
 */
export const GHOST_RENDER_ORDER = 8;

export class Electrodes {

	/**
	 * @param {{electrodes: Array<{position: number[], normal: number[], cell: number}>, cells: number}} grid
	 *   a grid of the electrode layout (GET /epg/layout)
	 * @param {{clippingPlanes?: import('three').Plane[]}} [options] the head's cutaway plane
	 */
	constructor( grid, { clippingPlanes = [] } = {} ) {

		const count = grid.electrodes.length;
		this.count = count;
		this.cells = Int32Array.from( grid.electrodes, ( e ) => e.cell );
		this.positions = Float64Array.from( grid.electrodes.flatMap( ( e ) => e.position ) );
		this.group = new Group();
		this.group.name = 'epg-electrodes';

		const dotGeometry = new SphereGeometry( ELECTRODE_SIZES.dot, 12, 8 );
		const squareGeometry = new BoxGeometry( ELECTRODE_SIZES.square, ELECTRODE_SIZES.square, ELECTRODE_SIZES.thickness );
		const solid = ( color ) => new MeshStandardMaterial( { color, roughness: 0.5, metalness: 0.1, clippingPlanes } );
		// CustomBlending (source alpha over) blends although `transparent` is false, which keeps the
		// pass in the opaque queue, drawn before the skin whatever the skin's transparency.
		const ghost = ( color ) => new MeshBasicMaterial( { color, opacity: GHOST_OPACITY, blending: CustomBlending, depthTest: false, depthWrite: false, clippingPlanes } );
		this.dots = new InstancedMesh( dotGeometry, solid( ELECTRODE_COLORS.dot ), count );
		this.squares = new InstancedMesh( squareGeometry, solid( ELECTRODE_COLORS.square ), count );
		this.ghostDots = new InstancedMesh( dotGeometry, ghost( ELECTRODE_COLORS.dot ), count );
		this.ghostSquares = new InstancedMesh( squareGeometry, ghost( ELECTRODE_COLORS.square ), count );
		// The ghosts draw the same instances: they share the matrices.
		this.ghostDots.instanceMatrix = this.dots.instanceMatrix;
		this.ghostSquares.instanceMatrix = this.squares.instanceMatrix;
		this.dots.name = 'epg-dots';
		this.squares.name = 'epg-squares';
		for ( const mesh of [ this.ghostDots, this.ghostSquares ] ) mesh.renderOrder = GHOST_RENDER_ORDER;
		for ( const mesh of [ this.dots, this.squares, this.ghostDots, this.ghostSquares ] ) {

			mesh.frustumCulled = false; // instances move between meshes; their bounds are small anyway
			this.group.add( mesh );

		}

		// One matrix per electrode and shape, built once: the square lies flat on the palate with
		// its sides along the row and across it.
		this.dotMatrices = new Float32Array( 16 * count );
		this.squareMatrices = new Float32Array( 16 * count );
		const m = new Matrix4(), n = new Vector3(), across = new Vector3(), along = new Vector3(), at = new Vector3();
		grid.electrodes.forEach( ( e, k ) => {

			n.fromArray( e.normal ).normalize();
			at.fromArray( e.position ).addScaledVector( n, ELECTRODE_SIZES.lift );
			across.set( 0, 0, 1 ).addScaledVector( n, - n.z );
			if ( across.lengthSq() < 1e-8 ) across.set( 1, 0, 0 );
			across.normalize();
			along.crossVectors( n, across );
			m.makeTranslation( at.x, at.y, at.z ).toArray( this.dotMatrices, 16 * k );
			m.makeBasis( across, along, n ).setPosition( at ).toArray( this.squareMatrices, 16 * k );

		} );
		this.contacted = 0;
		this.xray = null;
		this.show( null );
		this.setXray( false );

	}

	/**
	 * Show contacts: `frame[ cell ]` is 1 for a contacted electrode (the 64-cell Reading frame, or
	 * rows * columns cells for another grid); null shows every electrode as a dot.
	 */
	show( frame ) {

		const dots = this.dots.instanceMatrix.array, squares = this.squares.instanceMatrix.array;
		let d = 0, s = 0;
		for ( let k = 0; k < this.count; k ++ ) {

			if ( frame && frame[ this.cells[ k ] ] === 1 ) {

				for ( let i = 0; i < 16; i ++ ) squares[ 16 * s + i ] = this.squareMatrices[ 16 * k + i ];
				s ++;

			} else {

				for ( let i = 0; i < 16; i ++ ) dots[ 16 * d + i ] = this.dotMatrices[ 16 * k + i ];
				d ++;

			}

		}

		this.dots.count = this.ghostDots.count = d;
		this.squares.count = this.ghostSquares.count = s;
		this.dots.instanceMatrix.needsUpdate = true;
		this.squares.instanceMatrix.needsUpdate = true;
		this.contacted = s;

	}

	/** Show the faint see-through pass (while the skin is transparent or cut away). */
	setXray( on ) {

		on = Boolean( on );
		if ( on === this.xray ) return false;
		this.xray = on;
		this.ghostDots.visible = on;
		this.ghostSquares.visible = on;
		return true;

	}

	/**
	 * What window.glasshead.electrodes reports: the see-through pass and where each electrode is on
	 * the canvas (CSS pixels, from `viewer.screenRect`; null when behind the camera), its point in mm.
	 */
	probe( viewer ) {

		const at = new Box3();
		const points = [];
		for ( let k = 0; k < this.count; k ++ ) {

			at.min.fromArray( this.positions, 3 * k );
			this.group.localToWorld( at.min );
			at.max.copy( at.min );
			const rect = viewer.screenRect( at );
			points.push( { point: at.min.toArray(), x: rect?.x ?? null, y: rect?.y ?? null } );

		}

		return { xray: this.xray, colors: ELECTRODE_COLORS, points };

	}

	dispose() {

		this.group.removeFromParent();
		for ( const mesh of [ this.dots, this.squares ] ) mesh.geometry.dispose();
		for ( const mesh of [ this.dots, this.squares, this.ghostDots, this.ghostSquares ] ) {

			mesh.material.dispose();
			mesh.dispose();

		}

	}

}
