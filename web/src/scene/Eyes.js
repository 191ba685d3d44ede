// Eyeballs behind the face's eye openings, and upper lids that slide over them: the meshes, and the
// frame hook that turns the gaze toward the camera and blinks now and then. Placement, gaze and
// blink timing are pure functions in core/eyes.js.
//
// The eyes and lids belong to the skin's openings (userData.opening = 'eye'), so they fade and
// disappear with the skin (headAppearance.js); while the skin is not opaque, or cut away, the eyes
// look straight ahead and do not blink. Between blinks, with a still camera, the hook reports no
// change, so a still head draws nothing.

import { Box3, BufferAttribute, BufferGeometry, DoubleSide, Mesh, MeshStandardMaterial, Quaternion, SphereGeometry, Vector3 } from 'three';
import { domePatch } from '../core/openings.js';
import { approachAngle, blinkClosure, EYE_MOTION, eyeballPlacement, gazeBasis, gazeToward, lidPositions, nextBlinkDelay, restClosure } from '../core/eyes.js';
import { createEyeballMaterial, createLidMaterial, EYE_COLORS } from './eyeMaterials.js';
import { addSectionShading, TISSUE_COLORS } from './materials.js';

const Z = new Vector3( 0, 0, 1 );
const Y = new Vector3( 0, 1, 0 );
/** mm between the eyeball and the socket that holds it. */
const SOCKET_GAP_MM = 0.4;
const RAD = Math.PI / 180;

/**
 * The eyeball and the upper lid of one eye opening (`loop` of `positions`, frame from loopFrame),
 * given the height `bulge` (mm) of the dome that closes the opening behind them. `materials`
 * caches the shared materials across both eyes. Returns [eyeball, lid, socket].
 */
export function buildEyeMeshes( positions, loop, frame, bulge, materials ) {

	const eyeball = eyeballPlacement( positions, loop, frame );
	materials.eyeball ??= createEyeballMaterial( eyeball.radius );
	materials.lid ??= createLidMaterial();

	const sphere = new SphereGeometry( eyeball.radius, 48, 32 );
	sphere.rotateX( Math.PI / 2 ); // the pole, where the iris is drawn, along +z
	const ball = new Mesh( sphere, materials.eyeball );
	ball.name = 'eyeball';
	ball.position.fromArray( eyeball.centre );
	ball.userData.opening = 'eye';
	ball.userData.eye = { role: 'ball', centre: eyeball.centre, normal: frame.normal };

	// The lid: a patch across the opening just in front of the dome and of the eyeball.
	const patch = domePatch( positions, loop, frame, { rings: 12, bulge: bulge + EYE_MOTION.lidGap } );
	lidPositions( patch.positions, frame.normal, eyeball, EYE_MOTION.lidGap, patch.positions );
	let top = - Infinity, bottom = Infinity, half = 0;
	for ( let i = 0; i < patch.coords.length; i += 3 ) {

		top = Math.max( top, patch.coords[ i ] );
		bottom = Math.min( bottom, patch.coords[ i ] );
		half = Math.max( half, Math.abs( patch.coords[ i + 1 ] ) );

	}

	// Per vertex: height from the opening's bottom (0) to its top (1), and side (-1 to 1).
	const lidCoord = new Float32Array( 2 * ( patch.coords.length / 3 ) );
	for ( let i = 0, j = 0; i < patch.coords.length; i += 3, j += 2 ) {

		lidCoord[ j ] = ( patch.coords[ i ] - bottom ) / ( top - bottom );
		lidCoord[ j + 1 ] = patch.coords[ i + 1 ] / half;

	}

	const geometry = new BufferGeometry();
	geometry.setAttribute( 'position', new BufferAttribute( patch.positions, 3 ) );
	geometry.setAttribute( 'lidCoord', new BufferAttribute( lidCoord, 2 ) );
	geometry.setIndex( new BufferAttribute( patch.index, 1 ) );
	geometry.computeVertexNormals();
	const lid = new Mesh( geometry, materials.lid );
	lid.name = 'eyelid';
	lid.userData.opening = 'eye';
	lid.userData.eye = { role: 'lid', rest: restClosure( top, bottom ) };
	materials.lid.userData.lid.rest.value = lid.userData.eye.rest;
	materials.lid.side = DoubleSide;
	materials.socket ??= addSectionShading( new MeshStandardMaterial( { color: EYE_COLORS.sclera, roughness: 0.4, side: DoubleSide } ), { sectionColor: TISSUE_COLORS.skinCut } );
	return [ ball, lid, socketMesh( eyeball, frame.normal, materials.socket ) ];

}

/**
 * The orbit's soft tissue round the back of the eyeball: a sphere cap just outside the eyeball,
 * from the back pole to the plane of the opening's rim (which lies on the eyeball). The head is
 * hollow, so without it the eyeball would be seen from inside, through the cutaway's section,
 * floating in the forehead. Its faces point at the eyeball, as the tissue's surface does, so that
 * from inside the head it is drawn in the cut tissue's colour, like the skin's own inside; seen
 * from outside, past the eyeball's rim, it is sclera, as the dome closing the opening is.
 */
function socketMesh( eyeball, normal, material ) {

	const radius = eyeball.radius + SOCKET_GAP_MM;
	// From the back pole (theta = 0, along -normal) to the rim plane, `depth` in front of the centre.
	const rimTheta = Math.acos( Math.max( - 1, Math.min( 1, - eyeball.depth / radius ) ) );
	const geometry = new SphereGeometry( radius, 40, 20, 0, 2 * Math.PI, 0, rimTheta );
	flipFaces( geometry );
	const back = new Vector3().fromArray( normal ).negate().normalize();
	geometry.applyQuaternion( new Quaternion().setFromUnitVectors( Y, back ) );
	const socket = new Mesh( geometry, material );
	socket.name = 'eye-socket';
	socket.position.fromArray( eyeball.centre );
	socket.userData.opening = 'eye';
	socket.userData.eye = { role: 'socket' };
	return socket;

}

/** Turn a geometry inside out: reversed winding and normals. */
function flipFaces( geometry ) {

	const index = geometry.index.array;
	for ( let t = 0; t < index.length; t += 3 ) {

		const a = index[ t + 1 ];
		index[ t + 1 ] = index[ t + 2 ];
		index[ t + 2 ] = a;

	}

	const normals = geometry.getAttribute( 'normal' ).array;
	for ( let i = 0; i < normals.length; i ++ ) normals[ i ] = - normals[ i ];

}

/**
 * Drives the eyes of `head` in `viewer`: the gaze follows the camera within ±EYE_MOTION.gazeLimit
 * degrees, and with `blink` the lids close for EYE_MOTION.blinkDuration every few seconds.
 * `random` (a function returning [0, 1)) draws the delays between blinks.
 */
export class EyeMotion {

	constructor( head, viewer, { blink = true, random = Math.random } = {} ) {

		this.head = head;
		this.viewer = viewer;
		this.blinkEnabled = blink;
		this.random = random;
		this.balls = [];
		this.lidMaterial = null;
		for ( const part of head.parts.values() ) {

			for ( const mesh of part.meshes ) {

				if ( mesh.userData.eye?.role === 'ball' ) this.balls.push( mesh );
				if ( mesh.userData.eye?.role === 'lid' ) this.lidMaterial = mesh.material;

			}

		}

		this.gaze = [ 0, 0 ];
		this.target = [ 0, 0 ];
		this.closure = 0;
		this.blinkAge = - 1; // seconds into the current blink; negative between blinks
		this.untilBlink = nextBlinkDelay( this.random() );
		if ( this.balls.length === 0 ) return;

		this.basis = gazeBasis( this.balls.map( ( ball ) => ball.userData.eye.normal ) );
		this.middle = [ 0, 1, 2 ].map( ( k ) => this.balls.reduce( ( sum, ball ) => sum + ball.userData.eye.centre[ k ], 0 ) / this.balls.length );
		this.camera = new Vector3();
		this.direction = new Vector3();
		this.pose();
		this.removeHook = viewer.onFrame( ( dt ) => this.update( dt ) );

	}

	/** True while the eyes are shown as the skin's own (opaque, not cut away). */
	get alive() {

		return this.head.transparency === 0 && ! this.head.cutaway;

	}

	/** One frame: returns false when nothing changed (no redraw needed). */
	update( dt ) {

		const alive = this.alive;
		if ( alive ) {

			const camera = this.viewer.camera.getWorldPosition( this.camera );
			this.balls[ 0 ].parent?.worldToLocal( camera );
			gazeToward( camera.x, camera.y, camera.z, this.middle, this.basis, EYE_MOTION.gazeLimit, this.target );

		} else {

			this.target[ 0 ] = 0;
			this.target[ 1 ] = 0;

		}

		let changed = false;
		for ( let k = 0; k < 2; k ++ ) {

			if ( this.gaze[ k ] === this.target[ k ] ) continue;
			this.gaze[ k ] = approachAngle( this.gaze[ k ], this.target[ k ], dt );
			changed = true;

		}

		if ( changed ) this.pose();
		return this.updateBlink( dt, alive && this.blinkEnabled ) || changed;

	}

	/** Advance the blink clock; returns true when the lids moved. */
	updateBlink( dt, allowed ) {

		if ( this.blinkAge < 0 ) {

			this.untilBlink -= dt;
			if ( this.untilBlink > 0 || ! allowed ) {

				if ( this.untilBlink <= 0 ) this.untilBlink = nextBlinkDelay( this.random() );
				return this.setClosure( 0 );

			}

			this.blinkAge = 0;

		} else this.blinkAge += dt;

		if ( this.blinkAge >= EYE_MOTION.blinkDuration ) {

			this.blinkAge = - 1;
			this.untilBlink = nextBlinkDelay( this.random() );
			return this.setClosure( 0 );

		}

		this.setClosure( blinkClosure( this.blinkAge ) );
		return true;

	}

	setClosure( closure ) {

		if ( closure === this.closure ) return false;
		this.closure = closure;
		if ( this.lidMaterial ) this.lidMaterial.userData.lid.closure.value = closure;
		return true;

	}

	/** Turn each eyeball to the current gaze. */
	pose() {

		const { forward: f, up: u, side: s } = this.basis;
		const yaw = this.gaze[ 0 ] * RAD, pitch = this.gaze[ 1 ] * RAD;
		const a = Math.cos( pitch ) * Math.cos( yaw ), b = Math.cos( pitch ) * Math.sin( yaw ), c = Math.sin( pitch );
		this.direction.set( a * f[ 0 ] + b * s[ 0 ] + c * u[ 0 ], a * f[ 1 ] + b * s[ 1 ] + c * u[ 1 ], a * f[ 2 ] + b * s[ 2 ] + c * u[ 2 ] );
		for ( const ball of this.balls ) ball.quaternion.setFromUnitVectors( Z, this.direction );

	}

	/** What `window.glasshead.eyes` reports. */
	state() {

		return {
			count: this.balls.length,
			gaze: [ Math.round( this.gaze[ 0 ] * 10 ) / 10, Math.round( this.gaze[ 1 ] * 10 ) / 10 ],
			blinking: this.blinkAge >= 0,
			// Where each eyeball's centre falls on the canvas (CSS pixels), for tests that look there.
			centres: this.balls.map( ( ball ) => {

				const rect = this.viewer.screenRect?.( new Box3().setFromCenterAndSize( ball.getWorldPosition( new Vector3() ), new Vector3() ) );
				return { point: ball.userData.eye.centre.map( ( c ) => Math.round( c * 10 ) / 10 ), x: rect?.x ?? null, y: rect?.y ?? null };

			} ),
		};

	}

	dispose() {

		this.removeHook?.();

	}

}
