import assert from 'node:assert/strict';
import test from 'node:test';

import { EPG_CELLS } from '../../web/src/core/constants.js';
import { clinicianEpgReport, clinicianReport, formatIndexValue } from '../../web/src/ui/clinician/clinicianReport.js';

function framesWith( ...contactedPerFrame ) {

	const frames = new Uint8Array( contactedPerFrame.length * EPG_CELLS );
	contactedPerFrame.forEach( ( cells, k ) => {

		for ( const cell of cells ) frames[ k * EPG_CELLS + cell ] = 1;

	} );
	return frames;

}

test( 'an empty view reports nothing loaded and no contacts', () => {

	const state = { frame: 0, playing: false, loaded: false, error: null, speed: 1 };
	const report = clinicianReport( state, { frames: 0, targetFrame: -1, squares: null } );
	assert.equal( report.target, null );
	assert.equal( report.recording, null );
	assert.equal( report.agreement, null );
	const epg = clinicianEpgReport( state, -1 );
	assert.equal( epg.rows, null );
	assert.equal( epg.contacted, 0 );

} );

test( 'the EPG report shows the recording frame when there is one, else the target frame', () => {

	const recording = { frames: framesWith( [ 9, 10 ], [ 9, 10, 11 ] ) };
	const target = { frames: framesWith( [ 60 ] ) };
	const withRecording = clinicianEpgReport( { frame: 1, recording, target }, 0 );
	assert.equal( withRecording.contacted, 3 );
	assert.equal( withRecording.synthetic.contacted, 1 );
	const targetOnly = clinicianEpgReport( { frame: 0, target }, 0 );
	assert.equal( targetOnly.contacted, 1 );
	assert.equal( targetOnly.recording, null );

} );

test( 'index values show a dash when absent, one decimal from 10 up and three below', () => {

	assert.equal( formatIndexValue( null ), '–' );
	assert.equal( formatIndexValue( undefined ), '–' );
	assert.equal( formatIndexValue( 12.345 ), '12.3' );
	assert.equal( formatIndexValue( - 0.12345 ), '-0.123' );

} );
