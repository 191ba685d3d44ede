// The learner's tongue as estimated from their voice, drawn into the cut head as a ghost: the
// estimated tongue's mid-sagittal outline in the cutaway's plane, a faint fill inside a solid edge
// (a ribbon EDGE_MM wide: WebGL draws lines one pixel wide, too thin for a projector), over the
// anatomy, never hidden by the cut tongue it is compared with, which shows through the fill. It
// only shows what it is given: core/listen/inversion.js estimates, ui/listen/tongueProfile.js
// makes the curve.

import { BufferAttribute, BufferGeometry, DoubleSide, Group, Mesh, MeshBasicMaterial, Shape, ShapeGeometry } from 'three';

export const GHOST_COLOR = '#1565c0';
/** The edge's width, mm. */
export const EDGE_MM = 0.9;
/** Over the anatomy and the section caps. */
const RENDER_ORDER = 30;

/** Two triangles per segment of the closed curve, EDGE_MM wide about it (z = 0). */
function ribbon( curve ) {

	const count = curve.length / 2;
	const positions = new Float32Array( count * 18 );
	for ( let i = 0; i < count; i ++ ) {

		const j = ( i + 1 ) % count;
		const ax = curve[ 2 * i ], ay = curve[ 2 * i + 1 ], bx = curve[ 2 * j ], by = curve[ 2 * j + 1 ];
		const length = Math.hypot( bx - ax, by - ay ) || 1;
		const nx = - ( by - ay ) / length * EDGE_MM / 2, ny = ( bx - ax ) / length * EDGE_MM / 2;
		positions.set( [ ax - nx, ay - ny, 0, bx - nx, by - ny, 0, bx + nx, by + ny, 0, ax - nx, ay - ny, 0, bx + nx, by + ny, 0, ax + nx, ay + ny, 0 ], i * 18 );

	}

	return new BufferGeometry().setAttribute( 'position', new BufferAttribute( positions, 3 ) );

}

export class GhostTongue {

	constructor() {

		this.group = new Group();
		this.group.name = 'ghost-tongue';
		this.group.visible = false;
		const common = { depthTest: false, depthWrite: false, transparent: true };
		this.fill = new Mesh( new BufferGeometry(), new MeshBasicMaterial( { color: GHOST_COLOR, opacity: 0.16, side: DoubleSide, ...common } ) );
		this.edge = new Mesh( new BufferGeometry(), new MeshBasicMaterial( { color: GHOST_COLOR, side: DoubleSide, ...common } ) );
		for ( const object of [ this.fill, this.edge ] ) {

			object.renderOrder = RENDER_ORDER;
			object.frustumCulled = false;
			this.group.add( object );

		}

	}

	/** Show the closed curve (x y per point, mm, z = 0), or hide the ghost for null. */
	set( curve ) {

		if ( ! curve || curve.length < 6 ) {

			this.group.visible = false;
			return;

		}

		const outline = [];
		for ( let i = 0; i < curve.length; i += 2 ) outline.push( { x: curve[ i ], y: curve[ i + 1 ] } );
		this.edge.geometry.dispose();
		this.edge.geometry = ribbon( curve );
		this.fill.geometry.dispose();
		this.fill.geometry = new ShapeGeometry( new Shape( outline ) );
		this.group.visible = true;

	}

	get visible() {

		return this.group.visible;

	}

	dispose() {

		this.fill.geometry.dispose();
		this.fill.material.dispose();
		this.edge.geometry.dispose();
		this.edge.material.dispose();

	}

}
