// The outline of a mesh's cut by the mid-sagittal plane z = 0, drawn as dark line segments so that
// each tissue's section has a crisp edge, like an anatomical drawing.

import { BufferAttribute, BufferGeometry, LineBasicMaterial, LineSegments } from 'three';
import { planeSectionSegments } from '../core/section.js';

/** The outline sits this far (mm) on the viewer's side of the plane, in front of the caps. */
const OUTLINE_LIFT_MM = 0.05;

const outlineMaterial = new LineBasicMaterial( { color: '#4a2c2a', transparent: true, opacity: 0.85 } );

export class SectionOutline extends LineSegments {

	/** geometry: the mesh's BufferGeometry (positions in the parent's frame). */
	constructor( geometry ) {

		super( new BufferGeometry(), outlineMaterial );
		this.name = 'section-outline';
		this.renderOrder = 5;
		this.frustumCulled = false; // the draw range changes; the bounds would go stale
		this.update( geometry );

	}

	/** Recompute the outline for a changed geometry. Reallocates only when the mesh grew. */
	update( geometry ) {

		const positions = geometry.attributes.position.array;
		const index = geometry.index ? geometry.index.array : null;
		const triangles = index ? index.length / 3 : positions.length / 9;
		let attribute = this.geometry.getAttribute( 'position' );
		if ( ! attribute || attribute.array.length < 6 * triangles ) {

			attribute = new BufferAttribute( new Float32Array( 6 * triangles ), 3 );
			this.geometry.setAttribute( 'position', attribute );

		}

		const count = planeSectionSegments( positions, index, 0, attribute.array );
		for ( let i = 0; i < count * 2; i ++ ) attribute.array[ 3 * i + 2 ] -= OUTLINE_LIFT_MM;
		attribute.needsUpdate = true;
		this.geometry.setDrawRange( 0, count * 2 );
		this.segmentCount = count;

	}

}
