// The cranial cavity on the cutting plane (web/src/core/cranialRegion.js) and its layer
// (web/src/scene/CranialLayer.js), on a band shaped as the data's cranium is: a sheet round the
// back and sides of the head, open above, below and in front.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { BufferAttribute, BufferGeometry, Group } from 'three';

import { boundaryLoops, cranialRegion } from '../../web/src/core/cranialRegion.js';
import { insidePolygon } from '../../web/src/core/sectionPolygon.js';
import { BONE_STROKE_MM, CranialLayer, strokeStrip } from '../../web/src/scene/CranialLayer.js';
import { TISSUE_COLORS } from '../../web/src/scene/materials.js';

const CENTER_X = - 80, RADIUS = 70, BOTTOM = 50, TOP = 100, OPEN_DEG = 30;

/** The band: a cylinder about (CENTER_X, *, 0) from BOTTOM to TOP, open OPEN_DEG either side of +x. */
function band( steps = 41 ) {

	const positions = [];
	const index = [];
	for ( let k = 0; k <= steps; k ++ ) {

		const angle = ( OPEN_DEG + ( 360 - 2 * OPEN_DEG ) * k / steps ) * Math.PI / 180;
		const x = CENTER_X + RADIUS * Math.cos( angle ), z = RADIUS * Math.sin( angle );
		positions.push( x, BOTTOM, z, x, TOP, z );
		if ( k > 0 ) index.push( 2 * k - 2, 2 * k, 2 * k - 1, 2 * k - 1, 2 * k, 2 * k + 1 );

	}

	return { positions: Float32Array.from( positions ), index: Uint32Array.from( index ) };

}

function area( points ) {

	let sum = 0;
	const n = points.length / 2;
	for ( let i = 0, j = n - 1; i < n; j = i ++ ) sum += points[ 2 * j ] * points[ 2 * i + 1 ] - points[ 2 * i ] * points[ 2 * j + 1 ];
	return Math.abs( sum ) / 2;

}

test( 'a band has one boundary loop round its rims and front opening', () => {

	const { index } = band();
	const loops = boundaryLoops( index );
	assert.equal( loops.length, 1 );
	assert.equal( loops[ 0 ].length, 2 * 42 );

} );

test( 'the cavity is what the kept half of the band encloses, closed by its own section at the back', () => {

	const { positions, index } = band();
	const { outline, bone } = cranialRegion( positions, index );
	const front = CENTER_X + RADIUS * Math.cos( OPEN_DEG * Math.PI / 180 );
	const back = CENTER_X - RADIUS;
	// The projected rims are straight; the back follows the section of the polygonal cylinder.
	const expected = ( front - back ) * ( TOP - BOTTOM );
	assert.ok( Math.abs( area( outline ) - expected ) < 0.01 * expected, `area ${ area( outline ) } vs ${ expected }` );
	assert.ok( insidePolygon( outline, CENTER_X, ( BOTTOM + TOP ) / 2 ) );
	assert.ok( insidePolygon( outline, front - 1, BOTTOM + 1 ) );
	// No bone data above or below the band, nor in front of its opening: not cavity.
	assert.ok( ! insidePolygon( outline, CENTER_X, TOP + 5 ) );
	assert.ok( ! insidePolygon( outline, CENTER_X, BOTTOM - 5 ) );
	assert.ok( ! insidePolygon( outline, front + 5, ( BOTTOM + TOP ) / 2 ) );
	// The bone is the band's section at the occiput: a vertical line from the bottom to the top rim.
	assert.ok( bone.length >= 4 );
	for ( let k = 0; k < bone.length; k += 2 ) assert.ok( Math.abs( bone[ k ] - back ) < 0.5, `bone point at x ${ bone[ k ] }` );
	const ys = [ bone[ 1 ], bone[ bone.length - 1 ] ].sort( ( a, b ) => a - b );
	assert.ok( Math.abs( ys[ 0 ] - BOTTOM ) < 1e-3 && Math.abs( ys[ 1 ] - TOP ) < 1e-3, `bone from ${ ys }` );

} );

test( 'a closed mesh, or a band that does not reach the kept side, gives no region', () => {

	// A closed tetrahedron has no boundary.
	assert.deepEqual( boundaryLoops( [ 0, 1, 2, 0, 3, 1, 1, 3, 2, 2, 3, 0 ] ), [] );
	assert.equal( cranialRegion( new Float32Array( [ 0, 0, 1, 1, 0, 1, 0, 1, 1, 0, 0, 2 ] ), [ 0, 1, 2, 0, 3, 1, 1, 3, 2, 2, 3, 0 ] ), null );
	const { positions, index } = band();
	const right = Float32Array.from( positions );
	for ( let k = 2; k < right.length; k += 3 ) right[ k ] = - Math.abs( right[ k ] ) - 1;
	assert.equal( cranialRegion( right, index ), null );
	assert.equal( cranialRegion( positions, new Uint32Array( 0 ) ), null );

} );

test( 'the bone stroke lies inside the cavity, along its section', () => {

	const { positions, index } = band();
	const { outline, bone } = cranialRegion( positions, index );
	const { points, triangles } = strokeStrip( bone, outline, BONE_STROKE_MM );
	assert.equal( triangles.length, 6 * ( bone.length / 2 - 1 ) );
	for ( let k = 0; k < points.length; k += 4 ) {

		assert.ok( points[ k + 2 ] > points[ k ], 'the stroke widens toward the inside (anterior of the occiput)' );
		assert.ok( Math.abs( Math.hypot( points[ k + 2 ] - points[ k ], points[ k + 3 ] - points[ k + 1 ] ) - BONE_STROKE_MM ) < 1e-6 );

	}

} );

test( 'the layer fills the cavity in the brain colour, draws the bone, and follows the cut', () => {

	const { positions, index } = band();
	const geometry = new BufferGeometry();
	geometry.setAttribute( 'position', new BufferAttribute( positions, 3 ) );
	geometry.setIndex( new BufferAttribute( index, 1 ) );
	const layer = new CranialLayer( geometry );
	const group = new Group();
	layer.attach( group );
	assert.deepEqual( layer.meshes.map( ( mesh ) => mesh.name ), [ 'cranial-cavity', 'cranial-bone', 'cranial-rim' ] );
	assert.equal( group.children.length, 3 );
	assert.equal( `#${ layer.meshes[ 0 ].material.color.getHexString() }`, TISSUE_COLORS.brain );
	assert.equal( `#${ layer.meshes[ 1 ].material.color.getHexString() }`, TISSUE_COLORS.boneCut );
	assert.notEqual( TISSUE_COLORS.brain, TISSUE_COLORS.skinCut );
	assert.ok( layer.meshes.every( ( mesh ) => ! mesh.visible ) );
	layer.setVisible( true );
	assert.ok( layer.meshes.every( ( mesh ) => mesh.visible ) );
	const [ x, y, z ] = layer.innerPoint();
	assert.equal( z, 0 );
	assert.ok( insidePolygon( layer.region.outline, x, y ) );
	layer.dispose();
	assert.equal( group.children.length, 0 );

} );
