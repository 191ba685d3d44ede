// The neck's parts (web/src/scene/headAppearance.js): the head has no neck skin, so the spine,
// larynx and hyoid show only when the inside of the head is shown.
import { test } from 'node:test';
import assert from 'node:assert/strict';

import { NECK_PARTS, partShown } from '../../web/src/scene/headAppearance.js';

test( 'under an opaque, uncut head the neck parts are hidden and the rest shown', () => {

	for ( const name of NECK_PARTS ) assert.equal( partShown( name, 0, false ), false, name );
	for ( const name of [ 'tongue_rest', 'maxilla', 'velum_rest', 'pharynx', 'mandible' ] ) assert.equal( partShown( name, 0, false ), true, name );

} );

test( 'the neck parts show through a see-through skin and in the cutaway', () => {

	for ( const name of NECK_PARTS ) {

		assert.equal( partShown( name, 1, false ), true, name );
		assert.equal( partShown( name, 0, true ), true, name );

	}

} );

test( 'the neck parts are the spine, the larynx cartilages and the hyoid', () => {

	assert.deepEqual( [ ...NECK_PARTS ].sort(), [ 'arytenoid_left', 'arytenoid_right', 'cricoid', 'hyoid', 'thyroid', 'vertebrae' ] );

} );
