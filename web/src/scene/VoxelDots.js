// The collision voxel table drawn as dots at the voxel centres, coloured by class (the paper's
// Figure 3): ok (every point outside the palate: no test needed), borderline (the liner decides)
// and not ok (every point inside).

import { BufferAttribute, BufferGeometry, Group, Points, PointsMaterial } from 'three';
import { VOXEL_BORDER, VOXEL_NOT_OK, VOXEL_OK } from '../core/constants.js';

/** Dot colour, size (px) and opacity per class: the certain-outside dots stay in the background. */
export const VOXEL_STYLES = Object.freeze( {
	[ VOXEL_OK ]: Object.freeze( { name: 'ok', color: '#2f9e5a', size: 2, opacity: 0.5 } ),
	[ VOXEL_BORDER ]: Object.freeze( { name: 'borderline', color: '#e39a12', size: 3, opacity: 0.85 } ),
	[ VOXEL_NOT_OK ]: Object.freeze( { name: 'not ok', color: '#c62f2f', size: 3.5, opacity: 0.95 } ),
} );

/**
 * Centres of the voxels of one class (Float32Array, x y z each, project frame, mm).
 * Voxel ( ix, iy, iz ) is entry ( ix * ny + iy ) * nz + iz; its centre is
 * min + ( index + 0.5 ) / inv along each axis.
 * @param {object} tables from decodeCollisionTables()
 * @param {number} voxelClass VOXEL_OK, VOXEL_BORDER or VOXEL_NOT_OK
 */
export function voxelCentres( tables, voxelClass ) {

	const [ nx, ny, nz ] = tables.voxelShape;
	const voxels = tables.voxels;
	let count = 0;
	for ( let k = 0; k < voxels.length; k ++ ) if ( voxels[ k ] === voxelClass ) count ++;
	const centres = new Float32Array( 3 * count );
	let o = 0;
	for ( let ix = 0; ix < nx; ix ++ ) {

		for ( let iy = 0; iy < ny; iy ++ ) {

			for ( let iz = 0; iz < nz; iz ++ ) {

				if ( voxels[ ( ix * ny + iy ) * nz + iz ] !== voxelClass ) continue;
				centres[ o ++ ] = tables.voxelMin[ 0 ] + ( ix + 0.5 ) / tables.voxelInv[ 0 ];
				centres[ o ++ ] = tables.voxelMin[ 1 ] + ( iy + 0.5 ) / tables.voxelInv[ 1 ];
				centres[ o ++ ] = tables.voxelMin[ 2 ] + ( iz + 0.5 ) / tables.voxelInv[ 2 ];

			}

		}

	}

	return centres;

}

/** One Points object per voxel class (hidden until shown); `counts` gives the voxels per class name. */
export class VoxelDots extends Group {

	constructor( tables ) {

		super();
		this.name = 'collision-voxels';
		this.visible = false;
		this.counts = {};
		for ( const voxelClass of [ VOXEL_OK, VOXEL_BORDER, VOXEL_NOT_OK ] ) {

			const style = VOXEL_STYLES[ voxelClass ];
			const centres = voxelCentres( tables, voxelClass );
			this.counts[ style.name ] = centres.length / 3;
			if ( centres.length === 0 ) continue;
			const geometry = new BufferGeometry();
			geometry.setAttribute( 'position', new BufferAttribute( centres, 3 ) );
			const material = new PointsMaterial( {
				color: style.color, size: style.size, sizeAttenuation: false,
				transparent: true, opacity: style.opacity, depthWrite: false,
			} );
			const points = new Points( geometry, material );
			points.name = `voxels-${ style.name }`;
			points.renderOrder = 7;
			this.add( points );

		}

	}

	dispose() {

		for ( const points of this.children ) {

			points.geometry.dispose();
			points.material.dispose();

		}

		this.removeFromParent();

	}

}
