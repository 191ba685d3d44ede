// The workbench's parameter state (web/src/core/paramState.js): one Float32Array in the rigs'
// order, checked values, JSON copy and paste that refuses bad input and leaves the state as it
// was, and the workbench groups.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { readFileSync } from 'node:fs';
import { dirname, join } from 'node:path';
import { fileURLToPath } from 'node:url';

import { closestName, editDistance, GROUP_ORDER, parseParamsJson, ParamState, roundValue } from '../../web/src/core/paramState.js';

const HERE = dirname( fileURLToPath( import.meta.url ) );
const RIG = JSON.parse( readFileSync( join( HERE, '..', 'vectors', 'tongue-surface.json' ), 'utf8' ) ).fixtures.rig;

/** Lip parameters as the face rig defines them (appended after the tongue rig's). */
const LIPS = [
	{ name: 'lip_opening', unit: 'mm', min: 0, max: 50, neutral: 50, group: 'lips' },
	{ name: 'lip_rounding', unit: 'mm', min: - 4, max: 10, neutral: 0, group: 'lips' },
];

const fresh = () => new ParamState( [ ...RIG.parameters, ...LIPS ] );

test( 'a new state holds every parameter at its neutral value, in the rigs\' order', () => {

	const state = fresh();
	assert.equal( state.values.constructor, Float32Array );
	assert.deepEqual( state.names, [ ...RIG.parameters.map( ( p ) => p.name ), 'lip_opening', 'lip_rounding' ] );
	assert.equal( state.index.get( 'tip_height' ), RIG.parameters.findIndex( ( p ) => p.name === 'tip_height' ) );
	assert.equal( state.get( 'lip_opening' ), 50 );
	assert.equal( state.get( 'jaw_opening' ), 0 );
	assert.equal( state.version, 0 );

} );

test( 'setting a parameter changes its value, bumps the version and tells the listeners which', () => {

	const state = fresh();
	const heard = [];
	state.onChange( ( names ) => heard.push( names ) );
	assert.equal( state.set( 'tip_height', 5.5 ), true );
	assert.equal( state.get( 'tip_height' ), 5.5 );
	assert.equal( state.version, 1 );
	assert.equal( state.set( 'tip_height', 5.5 ), false, 'the same value again is no change' );
	assert.equal( state.version, 1 );
	assert.deepEqual( heard, [ [ 'tip_height' ] ] );

} );

test( 'an unknown name, a value out of range or not a number is refused and changes nothing', () => {

	const state = fresh();
	state.set( 'tip_height', 2 );
	const before = Float32Array.from( state.values );
	assert.throws( () => state.set( 'tip_heigth', 1 ), /Unknown parameter "tip_heigth": did you mean "tip_height"\?/ );
	assert.throws( () => state.set( 'tip_height', 40 ), /tip_height = 40 is outside its range -18 to 8 mm/ );
	assert.throws( () => state.set( 'tip_height', '3' ), /tip_height must be a number, got "3"/ );
	assert.throws( () => state.set( 'tip_height', Number.NaN ), /tip_height must be a finite number/ );
	assert.deepEqual( state.values, before );
	assert.equal( state.version, 1 );

} );

test( 'copied JSON lists every parameter in rig order, rounded, and pastes back to the same state', () => {

	const state = fresh();
	state.set( 'tip_height', 2.3 );
	state.set( 'jaw_opening', 7.5 );
	state.set( 'front_groove_depth', - 1.75 );
	const json = state.toJSON();
	const object = JSON.parse( json );
	assert.deepEqual( Object.keys( object ), state.names );
	assert.equal( object.tip_height, 2.3, 'float32 noise is rounded away' );
	assert.equal( object.front_groove_depth, - 1.75 );

	const other = fresh();
	assert.deepEqual( other.paste( json ), { ok: true } );
	assert.deepEqual( other.values, state.values );
	assert.deepEqual( other.toObject(), state.toObject() );

} );

test( 'pasting text that is not JSON shows why and leaves the state unchanged', () => {

	const state = fresh();
	state.set( 'blade_height', 3 );
	const before = Float32Array.from( state.values );
	const result = state.paste( '{"tip_height": 5,' );
	assert.equal( result.ok, false );
	assert.match( result.error, /^This is not valid JSON \(/ );
	assert.deepEqual( state.values, before );
	assert.equal( state.version, 1 );

} );

test( 'pasting an unknown parameter names it and changes nothing, not even the valid ones', () => {

	const state = fresh();
	const result = state.paste( JSON.stringify( { tip_height: 5, groove_deep: 2 } ) );
	assert.equal( result.ok, false );
	assert.match( result.error, /Unknown parameter "groove_deep"/ );
	assert.equal( state.get( 'tip_height' ), 0 );
	assert.equal( state.version, 0 );

} );

test( 'pasting a value out of range names the parameter and its range and changes nothing', () => {

	const state = fresh();
	const result = state.paste( '{"jaw_opening": 40}' );
	const jaw = RIG.parameters.find( ( p ) => p.name === 'jaw_opening' );
	assert.deepEqual( result, { ok: false, error: `jaw_opening = 40 is outside its range 0 to ${ jaw.max } deg.` } );
	const text = state.paste( '{"jaw_opening": "wide"}' );
	assert.equal( text.error, 'jaw_opening must be a number, got "wide".' );
	assert.equal( state.version, 0 );

} );

test( 'pasting something other than an object of names and values is explained', () => {

	const state = fresh();
	for ( const text of [ '[1, 2]', '42', 'null', '"tip_height"' ] ) {

		assert.match( state.paste( text ).error, /Expected a JSON object of parameter names and values/, text );

	}

	assert.equal( state.paste( '   ' ).error, 'Nothing to paste: the box is empty.' );
	assert.equal( state.version, 0 );

} );

test( 'a pasted subset sets those parameters and returns the others to neutral', () => {

	const state = fresh();
	state.set( 'dorsum_height', 4 );
	state.set( 'lip_opening', 10 );
	assert.equal( state.paste( '{"tip_advancement": 3}' ).ok, true );
	assert.equal( state.get( 'tip_advancement' ), 3 );
	assert.equal( state.get( 'dorsum_height' ), 0 );
	assert.equal( state.get( 'lip_opening' ), 50 );

} );

test( 'a saved pose, { name, params }, pastes as its params', () => {

	const state = fresh();
	const pose = { id: 3, name: 'alveolar stop', params: { tip_height: 6, jaw_opening: 4 } };
	assert.equal( state.paste( JSON.stringify( pose ) ).ok, true );
	assert.equal( state.get( 'tip_height' ), 6 );
	assert.equal( state.get( 'jaw_opening' ), 4 );
	assert.deepEqual( parseParamsJson( JSON.stringify( { params: { nope: 1 } } ), state ).ok, false );

} );

test( 'only the parameters away from neutral make the short form of a pose', () => {

	const state = fresh();
	state.set( 'tip_height', 1.25 );
	state.set( 'lip_opening', 20 );
	assert.deepEqual( state.changedFromNeutral(), { tip_height: 1.25, lip_opening: 20 } );

} );

test( 'reset returns every parameter to neutral and names those that moved', () => {

	const state = fresh();
	state.set( 'tip_height', 4 );
	state.set( 'lip_rounding', 2 );
	let heard = null;
	state.onChange( ( names ) => ( heard = names ) );
	assert.equal( state.reset(), true );
	assert.deepEqual( heard, [ 'tip_height', 'lip_rounding' ] );
	assert.deepEqual( state.values, state.neutral );
	assert.equal( state.reset(), false, 'nothing to reset' );

} );

test( 'writing values directly and touching the state counts as a change for everyone', () => {

	const state = fresh();
	let heard;
	state.onChange( ( names ) => ( heard = names ) );
	state.values[ state.index.get( 'body_height' ) ] = 2;
	state.touch();
	assert.equal( state.version, 1 );
	assert.equal( heard, null );

} );

test( 'the groups come in the workbench order: jaw, lips, velum, tongue sagittal, coronal front, middle, back', () => {

	const groups = fresh().groups();
	assert.deepEqual( groups.map( ( g ) => g.group ), GROUP_ORDER.filter( ( group ) => group !== 'velum' ) );
	assert.deepEqual( groups[ 0 ].parameters.map( ( p ) => p.name ), [ 'jaw_opening' ] );
	assert.equal( groups[ 2 ].parameters.length, 14 );
	for ( const g of groups.slice( 3 ) ) assert.equal( g.parameters.length, 7 );
	const velum = { name: 'velum_opening', unit: 'ratio', min: 0, max: 1, neutral: 0.76, group: 'velum' };
	const extra = new ParamState( [ ...RIG.parameters, { name: 'voicing', unit: 'ratio', min: 0, max: 1, neutral: 0, group: 'cues' }, velum ] );
	assert.equal( extra.groups().at( - 1 ).group, 'cues', 'groups outside the list come last' );
	assert.equal( extra.groups()[ 1 ].group, 'velum', 'the velum follows the jaw (and the lips)' );

} );

test( 'definitions with a repeated name or a neutral value out of range are refused', () => {

	assert.throws( () => new ParamState( [ LIPS[ 0 ], LIPS[ 0 ] ] ), /"lip_opening" is defined twice/ );
	assert.throws( () => new ParamState( [ { ...LIPS[ 1 ], neutral: 20 } ] ), /neutral 20 is not within \[-4, 10\]/ );
	assert.throws( () => new ParamState( [] ), /non-empty/ );

} );

test( 'typos are matched to the closest known name within two edits', () => {

	assert.equal( editDistance( 'kitten', 'sitting' ), 3 );
	assert.equal( editDistance( '', 'abc' ), 3 );
	assert.equal( closestName( 'jaw_openign', [ 'jaw_opening', 'tip_height' ] ), 'jaw_opening' );
	assert.equal( closestName( 'velum_height', [ 'jaw_opening', 'tip_height' ] ), null );
	assert.equal( roundValue( - 0.00001 ), 0 );
	assert.ok( Object.is( roundValue( - 0.00001 ), 0 ) );

} );
