// An observation on the tongue with its error vectors, as in Cohen, Beskow and Massaro (1998),
// Figures 5 and 6: the observed points, a line from each observed point P to where its ray from
// the origin first crosses the tongue (Q), and a sphere at P whose radius grows with |PQ|,
// coloured by the error's sign (the tongue beyond the observation, or short of it). The numbers
// come from core/rayError.js; this object only shows them.
//
// Two groups, one for each of the paper's figures. The outline (z = 0, Figure 5) lies in the
// cutaway's plane, where the tongue's cut is drawn: while the cutaway shows, it is drawn over
// everything and never clipped; without the cutaway it lies inside the tongue and is depth-tested
// like the anatomy. The surface (Figure 6) shows on the whole tongue only, depth-tested, so the
// tongue hides the points inside it: in the cutaway the view looks at the cut from the side the
// cut took away, and the surface's points would show only dimly, behind the cut and the air.

import { BufferAttribute, BufferGeometry, Color, DynamicDrawUsage, Group, InstancedMesh, LineBasicMaterial, LineSegments, Matrix4, MeshLambertMaterial, Points, PointsMaterial, SphereGeometry } from 'three';

export const OBSERVATION_COLORS = Object.freeze( { observed: '#16181d', beyond: '#f08c00', short: '#1c64d8' } );
/** Sphere radius (mm) at P: BASE + SLOPE |PQ|, at most MAX. */
export const SPHERE_RADIUS = Object.freeze( { base: 0.25, slope: 0.25, max: 2.5 } );
/** Over the section caps, the contact dots (8) and under the cue layer (20). */
const RENDER_ORDER = 12;

/** The radius (mm) of the sphere of an error of `distance` mm. */
export function sphereRadius( distance ) {

	return Math.min( SPHERE_RADIUS.max, SPHERE_RADIUS.base + SPHERE_RADIUS.slope * Math.abs( distance ) );

}

export class ObservationLayer {

	/** @param {{ isCut?: () => boolean }} options whether the cutaway shows now */
	constructor( { isCut = () => true } = {} ) {

		this.isCut = isCut;
		this.group = new Group();
		this.group.name = 'observation';
		this.group.visible = false;
		this.sphere = new SphereGeometry( 1, 12, 8 );
		this.colors = { beyond: new Color( OBSERVATION_COLORS.beyond ), short: new Color( OBSERVATION_COLORS.short ) };
		this.matrix = new Matrix4();
		this.parts = [];

	}

	/** Show the points of a createRayError() model (its outline and surface), replacing any before. */
	setModel( model ) {

		this.clearParts();
		this.model = model;
		const outline = this.part( 'observation-outline', 0, model.outlineCount, { onTop: true, pointSize: 5 } );
		const surface = this.part( 'observation-surface', model.outlineCount, model.count, { onTop: false, pointSize: 3 } );
		this.parts = [ outline, surface ].filter( Boolean );
		this.update();

	}

	part( name, from, to, { onTop, pointSize } ) {

		const count = to - from;
		if ( count === 0 ) return null;
		const common = { depthTest: ! onTop, depthWrite: ! onTop };
		const pointGeometry = new BufferGeometry();
		pointGeometry.setAttribute( 'position', new BufferAttribute( Float32Array.from( this.model.points.subarray( 3 * from, 3 * to ) ), 3 ) );
		const points = new Points( pointGeometry, new PointsMaterial( { color: OBSERVATION_COLORS.observed, size: pointSize, sizeAttenuation: false, ...common } ) );
		const lineGeometry = new BufferGeometry();
		lineGeometry.setAttribute( 'position', new BufferAttribute( new Float32Array( 6 * count ), 3 ) );
		lineGeometry.setAttribute( 'color', new BufferAttribute( new Float32Array( 6 * count ), 3 ) );
		const vectors = new LineSegments( lineGeometry, new LineBasicMaterial( { vertexColors: true, ...common } ) );
		const spheres = new InstancedMesh( this.sphere, new MeshLambertMaterial( { ...common, transparent: onTop, opacity: onTop ? 0.85 : 1 } ), count );
		spheres.instanceMatrix.setUsage( DynamicDrawUsage );
		const group = new Group();
		group.name = name;
		for ( const object of [ spheres, vectors, points ] ) {

			object.frustumCulled = false;
			object.renderOrder = onTop ? RENDER_ORDER : 0;
			// Read as each is drawn, so both follow the cutaway toggle without a hook.
			const material = object.material;
			if ( onTop ) object.onBeforeRender = () => ( material.depthTest = material.depthWrite = ! this.isCut() );
			else object.onBeforeRender = () => ( material.colorWrite = material.depthWrite = ! this.isCut() );
			group.add( object );

		}

		this.group.add( group );
		return { from, count, group, points, vectors, spheres };

	}

	/** Follow the model's last rayError(): the vectors P -> Q and the spheres' size and colour. */
	update() {

		const model = this.model;
		if ( ! model ) return;
		const { points: p, q, signed } = model;
		for ( const { from, count, vectors, spheres } of this.parts ) {

			const line = vectors.geometry.attributes.position.array;
			const color = vectors.geometry.attributes.color.array;
			for ( let i = 0; i < count; i ++ ) {

				const k = from + i;
				const c = signed[ k ] > 0 ? this.colors.beyond : this.colors.short;
				for ( let a = 0; a < 3; a ++ ) {

					line[ 6 * i + a ] = p[ 3 * k + a ];
					line[ 6 * i + 3 + a ] = q[ 3 * k + a ];

				}

				c.toArray( color, 6 * i );
				c.toArray( color, 6 * i + 3 );
				const r = sphereRadius( signed[ k ] );
				this.matrix.makeScale( r, r, r ).setPosition( p[ 3 * k ], p[ 3 * k + 1 ], p[ 3 * k + 2 ] );
				spheres.setMatrixAt( i, this.matrix );
				spheres.setColorAt( i, c );

			}

			vectors.geometry.attributes.position.needsUpdate = true;
			vectors.geometry.attributes.color.needsUpdate = true;
			spheres.instanceMatrix.needsUpdate = true;
			spheres.instanceColor.needsUpdate = true;

		}

	}

	clearParts() {

		for ( const { group, points, vectors, spheres } of this.parts ) {

			for ( const object of [ points, vectors ] ) {

				object.geometry.dispose();
				object.material.dispose();

			}

			spheres.material.dispose();
			spheres.dispose();
			this.group.remove( group );

		}

		this.parts = [];
		this.model = null;

	}

	dispose() {

		this.clearParts();
		this.sphere.dispose();
		this.group.removeFromParent();

	}

}
