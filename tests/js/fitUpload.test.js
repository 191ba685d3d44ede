// The fit page's pure parts (web/src/ui/fits/fitUpload.js): the kind chosen files make, the form
// POST /fits takes, and the words for a fit's progress and errors (ui/shared/targets.js).

import assert from 'node:assert/strict';
import { test } from 'node:test';
import { fitForm, fitKindFor, progressWords } from '../../web/src/ui/fits/fitUpload.js';
import { fitDescription, fitErrorWords } from '../../web/src/ui/shared/targets.js';

const file = ( name ) => new File( [ 'tongue_tip,20,10\n' ], name );
const none = { contour: null, epg: null, ema: null, surface: null };

test( 'one file is a fit of its kind, two or more of contour, EPG and sensors are combined', () => {

	assert.deepEqual( fitKindFor( none ), { kind: null, problem: 'Choose a file to fit.' } );
	assert.deepEqual( fitKindFor( { ...none, ema: file( 's.csv' ) } ), { kind: 'ema', problem: null } );
	assert.deepEqual( fitKindFor( { ...none, contour: file( 'a.csv' ), epg: file( 'n.json' ) } ), { kind: 'combined', problem: null } );
	const surface = fitKindFor( { ...none, surface: file( 't.obj' ), ema: file( 's.csv' ) } );
	assert.equal( surface.kind, null );
	assert.match( surface.problem, /surface is fitted alone/ );

} );

test( 'a single file goes as file; a combined fit sends each part with the weights that differ from 1', () => {

	const single = fitForm( { ...none, epg: file( 'n.json' ) }, { weights: { epg: 3 }, name: '  my /n/ ' } );
	assert.deepEqual( [ ...single.keys() ], [ 'kind', 'name', 'file' ] );
	assert.equal( single.get( 'kind' ), 'epg' );
	assert.equal( single.get( 'name' ), 'my /n/' );
	assert.equal( single.get( 'file' ).name, 'n.json' );

	const combined = fitForm( { ...none, contour: file( 'a.csv' ), ema: file( 's.csv' ) }, { weights: { contour: 1, ema: 2.5, epg: 4 } } );
	assert.deepEqual( [ ...combined.keys() ], [ 'kind', 'contour_file', 'ema_file', 'ema_weight' ] );
	assert.equal( combined.get( 'kind' ), 'combined' );
	assert.equal( combined.get( 'ema_weight' ), '2.5' );
	assert.equal( combined.get( 'ema_file' ).name, 's.csv' );
	assert.throws( () => fitForm( none ), /Choose a file/ );

} );

test( 'a fit with terms is described by each measurement’s error, others by RMS and agreement', () => {

	const report = { rms_mm: 0.19, terms: { contour: { weight: 1, rms_mm: 0.189 }, epg: { weight: 30, agreement: 0.871 }, ema: { weight: 20, rms_mm: 0.003 } } };
	assert.equal( fitErrorWords( report ), 'contour 0.19 mm RMS, EPG agreement 87 %, sensors 0.00 mm RMS' );
	assert.equal( fitDescription( { kind: 'combined', report } ), 'combined fit, contour 0.19 mm RMS, EPG agreement 87 %, sensors 0.00 mm RMS' );
	assert.equal( fitDescription( { kind: 'epg', report: { rms_mm: 1.234, agreement: 0.9 } } ), 'epg fit, RMS 1.23 mm, EPG agreement 90 %' );
	assert.equal( fitErrorWords( null ), '' );

} );

test( 'progress is told in evaluations and the best objective so far', () => {

	assert.equal( progressWords( { evaluations: 312, best_error: 1.0712, fraction: 0.2 } ), '312 evaluations, best 1.071' );
	assert.equal( progressWords( { evaluations: 0, best_error: null } ), '0 evaluations' );

} );
