// Per-frame upkeep of meshes that move only in part (core/movingMesh.js) and of the velum
// (VelumPose.js): the partial normals equal the full recompute, and the bounding spheres the
// scene keeps enclose the mesh in every pose (unit meshes, then the real head when built).
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { existsSync } from 'node:fs';

import { enclose, movingMesh, updateNormals } from '../../web/src/core/movingMesh.js';
import { vertexNormals } from '../../web/src/core/meshVolume.js';
import { blendNormals, enclosingSphere } from '../../web/src/scene/VelumPose.js';
import { nearArray } from './support/near.js';

/** A closed grid-like mesh: a UV sphere of rings x segments, with its poles. */
function uvSphere( rings = 10, segments = 16 ) {

	const positions = [ 0, 0, 10 ];
	for ( let r = 1; r < rings; r ++ ) {

		for ( let s = 0; s < segments; s ++ ) {

			const theta = Math.PI * r / rings;
			const phi = 2 * Math.PI * s / segments;
			positions.push( 10 * Math.sin( theta ) * Math.cos( phi ), 10 * Math.sin( theta ) * Math.sin( phi ), 10 * Math.cos( theta ) );

		}

	}

	positions.push( 0, 0, - 10 );
	const south = positions.length / 3 - 1;
	const at = ( r, s ) => 1 + ( r - 1 ) * segments + ( s % segments );
	const index = [];
	for ( let s = 0; s < segments; s ++ ) index.push( 0, at( 1, s ), at( 1, s + 1 ) );
	for ( let r = 1; r < rings - 1; r ++ ) {

		for ( let s = 0; s < segments; s ++ ) index.push( at( r, s ), at( r + 1, s ), at( r + 1, s + 1 ), at( r, s ), at( r + 1, s + 1 ), at( r, s + 1 ) );

	}

	for ( let s = 0; s < segments; s ++ ) index.push( south, at( rings - 1, s + 1 ), at( rings - 1, s ) );
	return { positions: Float32Array.from( positions ), index: Uint32Array.from( index ) };

}

function sphereHolds( sphere, positions, label ) {

	for ( let i = 0; i < positions.length; i += 3 ) {

		const d = Math.hypot( positions[ i ] - sphere.center.x, positions[ i + 1 ] - sphere.center.y, positions[ i + 2 ] - sphere.center.z );
		assert.ok( d <= sphere.radius, `${ label }: vertex ${ i / 3 } lies ${ d - sphere.radius } mm outside` );

	}

}

const fakeSphere = () => ( { center: { x: 0, y: 0, z: 0, set( x, y, z ) { this.x = x; this.y = y; this.z = z; } }, radius: 0 } );

test( 'normals redone around the moving vertices equal the full recompute, and the sphere holds the mesh', () => {

	const { positions, index } = uvSphere();
	const count = positions.length / 3;
	const moving = Uint32Array.from( { length: 40 }, ( _, k ) => 30 + k );
	const mesh = movingMesh( positions, index, moving );
	const normals = vertexNormals( positions, index, new Float64Array( 3 * count ), new Float32Array( 3 * count ) );
	const sphere = fakeSphere();
	for ( const push of [ 0, 3, - 4, 25 ] ) {

		for ( const v of moving ) positions[ 3 * v ] += push * Math.sin( v );
		updateNormals( mesh, positions, normals );
		const full = vertexNormals( positions, index, new Float64Array( 3 * count ), new Float32Array( 3 * count ) );
		nearArray( normals, full, 1e-6, `normals after a push of ${ push }` );
		sphereHolds( enclose( mesh, positions, sphere ), positions, `push ${ push }` );

	}

	const still = Math.sqrt( mesh.still );
	assert.ok( sphere.radius > still, 'the pushed vertices reach beyond the still ones' );

} );

test( 'blended velum normals are unit vectors; the sphere of the poses holds every blend of them', () => {

	const a = Float32Array.of( 1, 0, 0, 0, 0, 1 );
	const b = Float32Array.of( 0, 1, 0, 0, 0, 1 );
	const out = blendNormals( a, b, 0.5, new Float32Array( 6 ) );
	nearArray( out, [ Math.SQRT1_2, Math.SQRT1_2, 0, 0, 0, 1 ], 1e-7, 'halfway' );
	const poses = [ Float32Array.of( 0, 0, 0, 10, 0, 0 ), Float32Array.of( 0, 5, 0, 10, 5, 3 ), Float32Array.of( - 2, 0, 1, 12, 0, 0 ) ];
	const sphere = enclosingSphere( poses );
	for ( let u = 0; u <= 1; u += 0.125 ) {

		for ( const [ p, q ] of [ [ poses[ 0 ], poses[ 1 ] ], [ poses[ 1 ], poses[ 2 ] ] ] ) {

			sphereHolds( sphere, Float32Array.from( p, ( x, i ) => x * ( 1 - u ) + q[ i ] * u ), `u ${ u }` );

		}

	}

} );

const BUILD = new URL( '../../assets/build/', import.meta.url );
const built = [ 'manifest.json', 'tongue-rig.json', 'collision-tables.bin', 'face-rig.json', 'velum-rig.json' ].every( ( name ) => existsSync( new URL( name, BUILD ) ) );

test( 'on the real head: every face mesh and the velum stay inside their bounding spheres in every pose tried', { skip: built ? false : 'run glasshead build first' }, async () => {

	const { loadBuiltHead } = await import( './support/builtHead.js' );
	const { articulation } = await loadBuiltHead();
	const { state, faceRig, velum } = articulation;
	// The corners of the parameter box (jaw and lips; the tongue at random), then random poses.
	const lips = [ articulation.jawIndex, ...faceRig.lipIndex ];
	let seed = 7;
	const random = () => ( seed = ( seed * 16807 ) % 2147483647 ) / 2147483647;
	const poses = [];
	for ( let corner = 0; corner < 1 << lips.length; corner ++ ) {

		poses.push( state.minimum.map( ( low, k ) => {

			const bit = lips.indexOf( k );
			const share = bit >= 0 ? ( corner >> bit ) & 1 : random();
			return low + ( state.maximum[ k ] - low ) * share;

		} ) );

	}

	for ( let k = 0; k < 100; k ++ ) poses.push( state.minimum.map( ( low, i ) => low + ( state.maximum[ i ] - low ) * random() ) );
	for ( const pose of poses ) {

		state.values.set( pose );
		state.touch();
		articulation.update();
		for ( const { part } of faceRig.meshes ) sphereHolds( part.geometry.boundingSphere, part.geometry.attributes.position.array, part.name );
		sphereHolds( velum.geometry.boundingSphere, velum.positions, 'velum' );

	}

	// The face's normals are those of the full recompute, but where the seam welds them.
	const welded = new Set();
	const { members } = faceRig.seam;
	for ( const { part } of faceRig.meshes ) {

		const geometry = part.geometry;
		const count = geometry.attributes.position.count;
		const full = vertexNormals( geometry.attributes.position.array, geometry.index.array, new Float64Array( 3 * count ), new Float32Array( 3 * count ) );
		const skin = faceRig.seam.normals.indexOf( geometry.attributes.normal.array );
		welded.clear();
		for ( let k = 0; k < members.length; k += 2 ) if ( members[ k ] === skin ) welded.add( members[ k + 1 ] );
		const normals = geometry.attributes.normal.array;
		for ( let v = 0; v < count; v ++ ) {

			if ( welded.has( v ) ) continue;
			for ( let i = 0; i < 3; i ++ ) assert.ok( Math.abs( normals[ 3 * v + i ] - full[ 3 * v + i ] ) < 1e-5, `${ part.name } vertex ${ v }: normal ${ normals.subarray( 3 * v, 3 * v + 3 ) }, recomputed ${ full.subarray( 3 * v, 3 * v + 3 ) }` );

		}

	}

} );

test( 'on the real head: the velum\'s section from the triangles that can reach the plane is its full section at every opening', { skip: built ? false : 'run glasshead build first' }, async () => {

	const { createSectionPart, cutSection } = await import( '../../web/src/core/midSection.js' );
	const { loadBuiltHead } = await import( './support/builtHead.js' );
	const { articulation } = await loadBuiltHead();
	const { state, velum } = articulation;
	const few = velum.geometry.userData.midplaneTriangles;
	assert.ok( few.length < velum.triangles.length / 10, `${ few.length / 3 } of ${ velum.triangles.length / 3 } triangles` );
	const part = createSectionPart( few, velum.rig.vertexCount );
	const full = createSectionPart( velum.triangles, velum.rig.vertexCount );
	for ( let opening = 0; opening <= 1; opening += 1 / 64 ) {

		state.set( 'velum_opening', opening );
		articulation.update();
		cutSection( part, velum.positions );
		cutSection( full, velum.positions );
		assert.ok( part.pointCount > 0 );
		assert.deepEqual( Array.from( part.points.subarray( 0, 2 * part.pointCount ) ), Array.from( full.points.subarray( 0, 2 * full.pointCount ) ), `opening ${ opening }` );
		assert.deepEqual( Array.from( part.starts.subarray( 0, part.chainCount + 1 ) ), Array.from( full.starts.subarray( 0, full.chainCount + 1 ) ) );

	}

} );
