// The per-frame articulation pipeline (the data flow of the design: parameters -> jaw, lips,
// tongue surface -> collision correction -> hooks (EPG contacts) -> render).
//
// For the current parameters (a ParamState: one Float32Array in the rigs' order):
//   1. jaw: the mandible's Object3D matrix is the rig's jaw pose (the lower teeth are part of it);
//   2. tongue: the rig's JS evaluator writes the surface into preallocated arrays;
//   3. collision: the JS kernel corrects the vertices that went into the palate or teeth
//      (counts screened / tested / corrected), normals are recomputed when any moved;
//   4. the scene's tongue mesh (the parametric tongue replaces `tongue_rest`) shows them;
//   5. face: the face rig poses the skin and lips when one is given; without it the lower lip
//      rides on the jaw; the lips' mid-sagittal gap is measured either way;
//   3b. tract: with a velum rig, the velum is posed from velum_opening (VelumPose.js) and the
//      vertices that went into it or into the pharyngeal wall are moved back onto them
//      (core/tractCollision.js), before the normals;
//   6. hooks: onCorrected( fn ) gets the corrected Float32Array (EPG contacts read it).
// Nothing is recomputed while the parameters stay the same, and nothing is allocated per frame.

import { BufferAttribute, BufferGeometry, Matrix4 } from 'three';
import { jawPose, POSE_LENGTH } from '../core/jaw.js';
import { meshVolume, vertexNormals } from '../core/meshVolume.js';
import { TongueRig } from '../core/tongue.js';
import { correctVertices, STAT_CORRECTED, STAT_SCREENED, STAT_TESTED } from '../core/collision.js';
import { enclose, movingMesh } from '../core/movingMesh.js';
import { correctTract, createTractCollider, setTractPose, tractOrigin } from '../core/tractCollision.js';
import { velumSegment } from '../core/velum.js';
import { ParamState } from '../core/paramState.js';
import { registerDebug } from '../debug.js';
import { FacePose, lipGap, midlineLips } from './FacePose.js';
import { VelumPose } from './VelumPose.js';

/** The scene mesh the parametric tongue replaces. */
export const TONGUE_PART = 'tongue_rest';

/** Vertices reported in window.glasshead.tongue.samples: the poles and a spread of ring vertices. */
const SAMPLE_COUNT = 8;

export class Articulation {

	/**
	 * @param {TongueRig} rig the real-time tongue evaluator
	 * @param {ParamState} state its parameters first, in the rig's order (more may follow: lips)
	 * @param {{ tables?: object|null, faceRig?: object|null }} options parsed collision tables
	 *   (null: no correction) and a face rig (see setFaceRig)
	 */
	constructor( rig, state, { tables = null, faceRig = null } = {} ) {

		rig.parameters.forEach( ( p, k ) => {

			if ( state.names[ k ] !== p.name ) throw new Error( `parameter ${ k } is "${ state.names[ k ] }" in the state but "${ p.name }" in the tongue rig` );

		} );
		this.rig = rig;
		this.state = state;
		this.tables = tables;
		this.faceRig = faceRig;
		this.jawIndex = rig.jawParameter;

		const count = rig.vertexCount;
		this.vertexCount = count;
		this.surface = rig.createSurface();
		/** Corrected positions (Float32Array, xyz per vertex): the tongue the scene shows. */
		this.positions = new Float32Array( 3 * count );
		this.normals = new Float32Array( 3 * count );
		this.normalSums = new Float64Array( 3 * count );
		/** Per-vertex FLAG_SCREENED / FLAG_TESTED / FLAG_CORRECTED of the last frame. */
		this.flags = new Uint8Array( count );
		/** Screened, tested, corrected counts of the last frame (STAT_* order). */
		this.stats = new Int32Array( 3 );
		/** The velum and pharyngeal wall collider (setTract), its flags and counts. */
		this.tract = null;
		this.tractFlags = new Uint8Array( count );
		this.tractStats = new Int32Array( 3 );
		this.velum = null;
		/** Triangles of the tongue (Uint32Array, 3 per triangle); fixed. */
		this.triangles = rig.index;
		/** The posed sagittal control points (x y per point) and the hub of the last frame. */
		this.sagittalPoints = new Float64Array( 2 * rig.pointCount );
		this.hub = new Float64Array( 2 );
		/** Per station of the last frame: page direction (x y), radial controls, sideways stretch. */
		this.directions = new Float64Array( 2 * rig.stationCount );
		this.controls = new Float64Array( rig.stationCount * rig.controlCount );
		this.stationStretch = new Float64Array( rig.stationCount );
		this.jawPose = new Float64Array( POSE_LENGTH );
		this.jawMatrix = new Matrix4();
		this.volumeVersion = - 1;
		this.volumeMm3 = 0;
		this.lipGap = null;
		this.updates = 0;
		this.lastMs = 0;
		this.version = - 1;
		this.hooks = new Set();
		this.head = null;
		this.geometry = null;
		this.unregister = [];

	}

	/**
	 * Put the parametric tongue into the head in place of its rest tongue, and take over the
	 * mandible and the lips. Returns this.
	 */
	attach( head ) {

		const geometry = new BufferGeometry();
		geometry.setAttribute( 'position', new BufferAttribute( this.positions, 3 ) );
		geometry.setAttribute( 'normal', new BufferAttribute( this.normals, 3 ) );
		geometry.setIndex( new BufferAttribute( this.triangles, 1 ) );
		geometry.computeBoundingSphere();
		this.sphereMesh = movingMesh( this.positions, this.triangles, Uint32Array.from( { length: this.vertexCount }, ( _, v ) => v ) );
		const part = head.part( TONGUE_PART );
		if ( part ) {

			const old = part.geometry;
			head.setGeometry( TONGUE_PART, geometry );
			if ( old !== geometry ) old.dispose();

		}

		this.geometry = geometry;
		this.mandible = head.part( 'mandible' ) ?? null;
		for ( const name of [ 'mandible', 'lower_lip' ] ) {

			const group = head.part( name )?.group;
			if ( group ) group.matrixAutoUpdate = false;

		}

		this.lips = midlineLips( head );
		this.head = head;
		this.update( true );
		return this;

	}

	/**
	 * Use a face rig for the skin and lips: an object with pose( values, jawPose ) (the state's
	 * values, the row-major 3 x 4 jaw pose) that moves their vertices and returns the lip gap in
	 * mm, such as a FacePose. null goes back to the rigid lower lip.
	 */
	setFaceRig( faceRig ) {

		this.faceRig = faceRig;
		this.version = - 1;

	}

	/**
	 * Collide the tongue with the velum (posed by this.velum) and the pharyngeal wall: a collider
	 * from tractColliderFor(), or null for the palate alone.
	 */
	setTract( collider ) {

		this.tract = collider;
		this.version = - 1;

	}

	/** Recompute when the parameters changed since the last call (or when forced). Returns whether it did. */
	update( force = false ) {

		if ( ! force && this.version === this.state.version ) return false;
		const start = performance.now();
		this.version = this.state.version;
		const values = this.state.values;
		const rig = this.rig;

		// Normals once, from the corrected positions (step 3), not from the surface as well.
		rig.evaluate( values, this.surface, false );
		this.sagittalPoints.set( rig.points );
		this.hub.set( rig.hub );
		this.directions.set( rig.direction );
		this.controls.set( rig.controls );
		this.stationStretch.set( rig.stationStretch );
		this.positions.set( this.surface.positions );
		if ( this.tables ) correctVertices( this.positions, this.vertexCount, this.tables, this.flags, this.stats );
		else this.stats.fill( 0 );
		if ( this.tract && this.velum ) {

			const velum = this.velum;
			velum.pose( values );
			const first = velumSegment( velum.rig, values[ velum.index ] );
			setTractPose( this.tract, 0, velum.positions, first, velum.rig.share[ 0 ] );
			correctTract( this.positions, this.vertexCount, this.tract, this.tractFlags, this.tractStats );

		} else this.tractStats.fill( 0 );

		vertexNormals( this.positions, this.triangles, this.normalSums, this.normals );

		jawPose( values[ this.jawIndex ], rig.jaw, this.jawPose );
		const p = this.jawPose;
		this.jawMatrix.set( p[ 0 ], p[ 1 ], p[ 2 ], p[ 3 ], p[ 4 ], p[ 5 ], p[ 6 ], p[ 7 ], p[ 8 ], p[ 9 ], p[ 10 ], p[ 11 ], 0, 0, 0, 1 );
		if ( this.head ) this.pose();

		for ( const hook of this.hooks ) hook( this.positions, this );
		this.updates ++;
		this.lastMs = performance.now() - start;
		return true;

	}

	/** Volume of the corrected tongue, mm^3 (computed when asked, once per frame at most). */
	get volume() {

		if ( this.volumeVersion !== this.version ) {

			this.volumeMm3 = meshVolume( this.positions, this.triangles );
			this.volumeVersion = this.version;

		}

		return this.volumeMm3;

	}

	/** Steps 1, 4 and 5 in the scene. */
	pose() {

		setMatrix( this.mandible?.group, this.jawMatrix );
		if ( this.faceRig ) {

			setMatrix( this.head.part( 'lower_lip' )?.group, IDENTITY );
			this.lipGap = this.faceRig.pose( this.state.values, this.jawPose );

		} else {

			setMatrix( this.head.part( 'lower_lip' )?.group, this.jawMatrix );
			this.lipGap = this.lips ? lipGap( this.lips, this.jawPose ) : null;

		}

		this.velum?.pose( this.state.values );
		const geometry = this.geometry;
		if ( ! geometry ) return;
		geometry.attributes.position.needsUpdate = true;
		geometry.attributes.normal.needsUpdate = true;
		// Every tongue vertex moves: measured from a fixed centre in one pass.
		enclose( this.sphereMesh, this.positions, geometry.boundingSphere );
		const part = this.head.part( TONGUE_PART );
		if ( part?.geometry === geometry ) {

			// As Head.updateVertices: the section outline follows now if it shows, else when it does.
			if ( this.head.cutaway ) part.outline.update( geometry );
			else part.outlineStale = true;

		}

	}

	/**
	 * Call fn( correctedPositions, articulation ) after every recompute, with the corrected
	 * Float32Array (xyz per vertex; the same array every time, `triangles` its index). Returns a
	 * function that removes the hook.
	 */
	onCorrected( fn ) {

		this.hooks.add( fn );
		return () => this.hooks.delete( fn );

	}

	/** Recompute from the viewer's loop; the scene is drawn only in frames that changed. */
	attachViewer( viewer ) {

		this.unregister.push( viewer.onFrame( () => this.update() ) );
		return this;

	}

	/** What window.glasshead reports about the tongue: sizes, volume, a checksum and samples. */
	tongueReport() {

		const positions = this.positions;
		let checksum = 0;
		let tip = 0;
		let top = 0;
		for ( let v = 0; v < this.vertexCount; v ++ ) {

			const o = 3 * v;
			checksum += ( 1 + ( v % 7 ) ) * ( positions[ o ] + 2 * positions[ o + 1 ] + 3 * positions[ o + 2 ] );
			if ( positions[ o ] > positions[ 3 * tip ] ) tip = v;
			if ( positions[ o + 1 ] > positions[ 3 * top + 1 ] ) top = v;

		}

		const vertex = ( v ) => Array.from( positions.subarray( 3 * v, 3 * v + 3 ), round3 );
		const samples = [];
		for ( let s = 0; s < SAMPLE_COUNT; s ++ ) {

			const v = Math.round( s * ( this.vertexCount - 1 ) / ( SAMPLE_COUNT - 1 ) );
			samples.push( { vertex: v, position: vertex( v ) } );

		}

		return {
			vertexCount: this.vertexCount,
			triangleCount: this.triangles.length / 3,
			volumeMm3: round3( this.volume ),
			checksum: round3( checksum ),
			tip: vertex( tip ),
			top: vertex( top ),
			samples,
		};

	}

	/** Add params, tongue, collision and lipGap to window.glasshead (removed by dispose()). */
	registerDebugFields() {

		const fields = {
			params: () => this.state.toObject(),
			tongue: () => this.tongueReport(),
			collision: () => ( {
				enabled: this.tables !== null,
				screened: this.stats[ STAT_SCREENED ],
				tested: this.stats[ STAT_TESTED ],
				corrected: this.stats[ STAT_CORRECTED ],
				tract: {
					enabled: this.tract !== null,
					tested: this.tractStats[ STAT_TESTED ],
					corrected: this.tractStats[ STAT_CORRECTED ],
				},
				updates: this.updates,
				ms: round3( this.lastMs ),
			} ),
			lipGap: () => ( this.lipGap === null ? null : round3( this.lipGap ) ),
		};
		for ( const [ name, getter ] of Object.entries( fields ) ) this.unregister.push( registerDebug( name, getter ) );
		return this;

	}

	dispose() {

		for ( const unregister of this.unregister ) unregister();
		this.unregister = [];
		this.hooks.clear();

	}

}

const IDENTITY = new Matrix4();

/** The scene mesh of the posterior pharyngeal wall. */
export const PHARYNX_PART = 'pharynx';

/**
 * The tract collider for a posed velum (a VelumPose) and the head's pharyngeal wall; null when
 * the head has no wall (the tongue then meets the palate alone).
 */
export function tractColliderFor( velum, head ) {

	const wall = head.part( PHARYNX_PART )?.geometry;
	if ( ! wall?.index ) return null;
	return createTractCollider( tractOrigin( velum.rig.poses ), [
		{ name: 'velum', poses: velum.rig.poses, triangles: velum.triangles },
		{ name: 'pharynx', poses: [ wall.getAttribute( 'position' ).array ], triangles: Uint32Array.from( wall.index.array ) },
	] );

}

function setMatrix( group, matrix ) {

	if ( ! group ) return;
	group.matrix.copy( matrix );
	group.matrixWorldNeedsUpdate = true;

}

function round3( value ) {

	return Math.round( value * 1000 ) / 1000;

}

/**
 * Parameter definitions of the tongue rig followed by those of the face rig (its lips) and of the
 * velum rig (velum_opening), the tongue's first so that its evaluator reads the same array.
 */
export function parameterDefinitions( rigDefinition, faceRigDefinition = null, velumRigDefinition = null ) {

	const tongue = rigDefinition.parameters;
	const names = new Set( tongue.map( ( p ) => p.name ) );
	const lips = ( faceRigDefinition?.parameters ?? [] ).filter( ( p ) => ! names.has( p.name ) );
	for ( const p of lips ) names.add( p.name );
	const velum = ( velumRigDefinition?.parameters ?? [] ).filter( ( p ) => ! names.has( p.name ) );
	return [ ...tongue, ...lips, ...velum ];

}

/**
 * Put a parametric, collision corrected tongue into `head`, with the face following the jaw and
 * the lip parameters, driven from `viewer`'s loop (none: updates are the caller's). The data are
 * what the views load (ui/shared/loaders.js loadArticulationData): the tongue rig definition, the decoded
 * collision tables and the face rig definition. Tables or a face rig that could not be had (null)
 * leave the tongue uncorrected (collision.enabled false) or the lower lip riding rigidly on the
 * jaw, with `tablesError` or `faceRigError` saying why; a velum rig (null: the velum stays at
 * rest, `velumError` says why) poses the velum from velum_opening. Returns the Articulation, its
 * debug fields registered.
 * @param {{ definition: object, tables?: object|null, tablesError?: string|null,
 *   face?: object|null, faceRigError?: string|null, velum?: object|null,
 *   velumError?: string|null }} data
 */
export function createArticulation( head, viewer, { definition, tables = null, tablesError = null, face = null, faceRigError = null, velum = null, velumError = null } ) {

	const rig = new TongueRig( definition );
	const state = new ParamState( parameterDefinitions( definition, face, velum ) );
	const articulation = new Articulation( rig, state, { tables } );
	articulation.tablesError = tablesError;
	articulation.faceRigError = faceRigError;
	articulation.attach( head );
	if ( face ) {

		try {

			articulation.setFaceRig( new FacePose( face, head, state ) );
			articulation.update( true );

		} catch ( error ) {

			articulation.faceRigError = error.message;

		}

	}

	articulation.velumError = velumError;
	if ( velum ) {

		try {

			articulation.velum = new VelumPose( velum, head, state );
			articulation.unregister.push( articulation.velum.registerDebugField() );
			articulation.setTract( tractColliderFor( articulation.velum, head ) );
			articulation.update( true );

		} catch ( error ) {

			articulation.velumError = error.message;

		}

	}

	articulation.registerDebugFields();
	if ( viewer ) articulation.attachViewer( viewer );
	return articulation;

}
