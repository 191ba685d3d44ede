// The cue layer: what the voice and the air do, drawn without words in the mid-sagittal plane, so
// that it shows on the cutaway's cut and through the transparent skin.
//   - voicing: golden rings widening from the glottis and a glow there that buzzes;
//   - oral airflow: blue dots with fading trails streaming from the glottis along the tract's
//     midline and out of the lips; when the narrowest constriction is closed (the tongue against
//     the palate, the lips together) or the air goes out of the nose instead (a nasal's open
//     port beside a sealed mouth), they gather behind it and none passes it;
//   - turbulence: an orange swirl of jittering dots at the narrowest constriction, when the air
//     through it is loud enough to hiss (core/cues.js constrictionAirflow: its area, the glottis's
//     and the nasal port's give the flow, and the flow and the area the noise);
//   - nasal airflow: magenta dots streaming up the pharynx, through the nasal port and out of the
//     nose, as many and as fast as the port's area allows (none when the velum is raised).
// The layouts are core/cues.js; nothing is allocated per frame. Drawn over everything (no depth
// test) and never clipped by the cutaway.

import {
	AdditiveBlending, BufferAttribute, BufferGeometry, CanvasTexture, DoubleSide, Group, Mesh, MeshBasicMaterial,
	NormalBlending, PlaneGeometry, Points, PointsMaterial, RingGeometry,
} from 'three';
import {
	arcLengthAt, constrictionAirflow, layoutFlow, layoutRings, layoutSwirl, nasalPath, nasalStrength,
	oralPath,
} from '../core/cues.js';
import { CONSTRICTION_FLOOR, CONSTRICTION_FOUND, CONSTRICTION_ROOF, CONSTRICTION_WIDTH } from '../core/constriction.js';

export const CUE_COLORS = Object.freeze( { voicing: '#ffb000', oral: '#0a5cff', nasal: '#d4148c', turbulence: '#ff5a00' } );

/** Particles, trail dots and speeds of the flows (mm, mm/s); rings of the voice. */
const ORAL = Object.freeze( { count: 30, trail: 6, speed: 70, spacingMm: 2.4, spreadMm: 2.4, sizeMm: 5.5, seed: 11 } );
const NASAL = Object.freeze( { count: 20, trail: 6, speed: 45, spacingMm: 2.4, spreadMm: 1.8, sizeMm: 5.5, seed: 57 } );
const SWIRL = Object.freeze( { count: 40, radiusMm: 6, sizeMm: 4.5, seed: 101 } );
const RINGS = Object.freeze( { count: 3, periodS: 0.75, innerMm: 4, outerMm: 16 } );
/** The glow's radius (mm) and its buzz (Hz, shown slower than a voice's 100 to 300 Hz). */
const GLOW = Object.freeze( { radiusMm: 7, buzzHz: 9 } );
/** Above the air layer and section caps (render orders up to about 3) and the contact dots (8). */
const RENDER_ORDER = 20;

export class CueLayer {

	/**
	 * @param {{ glottis: number[], port: number[]|null, midline: Float64Array,
	 *   constriction: Float64Array|null, portArea: () => number }} options the glottis and the
	 *   nasal port (x y, mm, from GET /anatomy/landmarks), the tract's midline from the lips
	 *   (tractMidline), the live constriction result (core/constriction.js layout) and the nasal
	 *   port's current area (mm²); `voiced()` whether the voice sounds now (a speech player's
	 *   voicing track, or the workbench's phoneme target; always, by default); `sound()` the phoneme features
	 *   ({ voiced, manner }, GET /phonemes) of the sound made now, or null for none: they set the
	 *   glottis and say whether the constriction is a closure or a channel (core/cues.js)
	 */
	constructor( { glottis, port, midline, constriction = null, portArea = () => 0, voiced = () => true, sound = () => null } ) {

		this.glottis = glottis;
		this.voiced = voiced;
		this.sound = sound;
		this.air = { glottisMm2: 0, areaMm2: 0, total: 0, oral: 0, nasal: 0, levelDb: - Infinity, turbulence: 0, passes: true };
		this.constriction = constriction;
		this.portArea = portArea;
		this.oralPath = oralPath( midline, glottis );
		this.nasalPath = port ? nasalPath( midline, glottis, port ) : null;
		this.cues = { visible: false, voicing: true, nasal: true, oral: true };
		this.shown = { turbulence: false, nasalStrength: 0, turbulenceStrength: 0, oralStopped: false, oralStopMm: null, oralReachMm: 0, oralFrontX: null };

		this.group = new Group();
		this.group.name = 'cue-layer';
		this.group.visible = false;
		this.texture = dotTexture();
		this.oral = this.points( 'cue-oral', ORAL.count * ORAL.trail, CUE_COLORS.oral, ORAL.sizeMm );
		this.nasal = this.points( 'cue-nasal', NASAL.count * NASAL.trail, CUE_COLORS.nasal, NASAL.sizeMm );
		this.swirl = this.points( 'cue-turbulence', SWIRL.count, CUE_COLORS.turbulence, SWIRL.sizeMm );
		this.rings = [];
		this.ringGeometry = new RingGeometry( 0.8, 1, 48 );
		for ( let k = 0; k < RINGS.count; k ++ ) {

			const ring = new Mesh( this.ringGeometry, cueMaterial( new MeshBasicMaterial( { color: CUE_COLORS.voicing, side: DoubleSide } ) ) );
			ring.position.set( glottis[ 0 ], glottis[ 1 ], 0 );
			ring.name = 'cue-voicing-ring';
			this.rings.push( ring );

		}

		this.glowGeometry = new PlaneGeometry( 2, 2 );
		this.glow = new Mesh( this.glowGeometry, cueMaterial( new MeshBasicMaterial( { color: CUE_COLORS.voicing, map: this.texture, side: DoubleSide, blending: AdditiveBlending } ) ) );
		this.glow.name = 'cue-voicing-glow';
		this.glow.position.set( glottis[ 0 ], glottis[ 1 ], 0 );
		this.voicing = new Group();
		this.voicing.add( this.glow, ...this.rings );
		this.group.add( this.oral, this.nasal, this.swirl, this.voicing );
		for ( const object of [ this.oral, this.nasal, this.swirl, this.glow, ...this.rings ] ) {

			object.renderOrder = RENDER_ORDER;
			object.frustumCulled = false;

		}

		this.radii = new Float64Array( 2 * RINGS.count );
		// Layout options, made once and updated each frame.
		this.options = {
			oral: { ...ORAL, time: 0, alpha: 1, stopMm: Infinity, reachMm: 0 },
			nasal: { ...NASAL, time: 0, alpha: 1 },
			swirl: { count: SWIRL.count, time: 0, strength: 0, radiusMm: SWIRL.radiusMm, seed: SWIRL.seed },
		};

	}

	points( name, count, color, size ) {

		const geometry = new BufferGeometry();
		geometry.setAttribute( 'position', new BufferAttribute( new Float32Array( 3 * count ), 3 ) );
		// White with an alpha per dot: the material's colour tints it; three.js reads 4 components as alpha.
		geometry.setAttribute( 'color', new BufferAttribute( new Float32Array( 4 * count ).fill( 1 ), 4 ) );
		geometry.setDrawRange( 0, 0 );
		const material = cueMaterial( new PointsMaterial( { color, size, sizeAttenuation: true, map: this.texture, vertexColors: true, blending: NormalBlending } ) );
		const points = new Points( geometry, material );
		points.name = name;
		return points;

	}

	/** Switch the layer ({ visible }) and the cues ({ voicing, nasal, oral }) on or off. */
	set( cues ) {

		Object.assign( this.cues, cues );
		this.group.visible = this.cues.visible;

	}

	/** True while something is drawn that moves (so the scene must be redrawn every frame). */
	get animating() {

		const c = this.cues;
		return c.visible && ( c.voicing || c.oral || ( c.nasal && this.shown.nasalStrength > 0 ) );

	}

	/** Lay the cues out for time t (s); returns whether anything moving is drawn. */
	update( t ) {

		const c = this.cues;
		const area = this.portArea();
		const nasal = nasalStrength( area );
		const r = this.constriction;
		const width = r && r[ CONSTRICTION_FOUND ] ? r[ CONSTRICTION_WIDTH ] : Infinity;
		// A closure, or a mouth so much narrower than the open port that the air leaves by the
		// nose, stops the oral flow there; no air passes, so no turbulence either.
		const air = constrictionAirflow( width, area, this.sound(), this.air );
		const closed = ! air.passes;
		const turbulence = air.turbulence;
		this.shown.nasalStrength = nasal;
		this.shown.turbulenceStrength = turbulence;
		this.shown.turbulence = c.visible && c.oral && turbulence > 0;
		this.shown.oralStopped = closed;
		this.options.oral.stopMm = closed ? arcLengthAt( this.oralPath, ( r[ CONSTRICTION_FLOOR ] + r[ CONSTRICTION_ROOF ] ) / 2, ( r[ CONSTRICTION_FLOOR + 1 ] + r[ CONSTRICTION_ROOF + 1 ] ) / 2 ) : Infinity;
		this.shown.oralStopMm = closed ? this.options.oral.stopMm : null;
		if ( ! c.visible ) return false;

		this.flow( this.oral, c.oral ? this.oralPath : null, this.options.oral, t, 1, ORAL.count );
		this.shown.oralReachMm = c.oral ? this.options.oral.reachMm : 0;
		this.shown.oralFrontX = c.oral ? frontX( this.oral.geometry ) : null;
		const nasalCount = Math.max( 4, Math.round( NASAL.count * nasal ) );
		this.flow( this.nasal, c.nasal && nasal > 0 ? this.nasalPath : null, this.options.nasal, t * ( 0.5 + 0.5 * nasal ), 0.5 + 0.5 * nasal, nasalCount );

		this.swirl.visible = this.shown.turbulence;
		if ( this.swirl.visible ) {

			const cx = ( r[ CONSTRICTION_FLOOR ] + r[ CONSTRICTION_ROOF ] ) / 2;
			const cy = ( r[ CONSTRICTION_FLOOR + 1 ] + r[ CONSTRICTION_ROOF + 1 ] ) / 2;
			const geometry = this.swirl.geometry;
			const options = this.options.swirl;
			options.time = t;
			options.strength = turbulence;
			layoutSwirl( cx, cy, options, geometry.attributes.position.array, geometry.attributes.color.array, 0, 4, 3 );
			geometry.setDrawRange( 0, SWIRL.count );
			geometry.attributes.position.needsUpdate = true;
			geometry.attributes.color.needsUpdate = true;

		}

		this.voicing.visible = c.voicing && this.voiced();
		if ( this.voicing.visible ) {

			layoutRings( t, RINGS.count, RINGS.periodS, RINGS.innerMm, RINGS.outerMm, this.radii );
			for ( let k = 0; k < RINGS.count; k ++ ) {

				this.rings[ k ].scale.setScalar( this.radii[ 2 * k ] );
				this.rings[ k ].material.opacity = this.radii[ 2 * k + 1 ];

			}

			const buzz = 1 + 0.18 * Math.sin( 2 * Math.PI * GLOW.buzzHz * t );
			this.glow.scale.setScalar( GLOW.radiusMm * buzz );
			// A small shake along the folds' vibration (up and down), as a child's buzzing drawing.
			this.glow.position.y = this.glottis[ 1 ] + 0.6 * Math.sin( 2 * Math.PI * GLOW.buzzHz * 1.7 * t );

		}

		return this.animating;

	}

	/** One flow's dots, or none (path null); `options` are its layout options, updated here. */
	flow( points, path, options, time, alpha, count ) {

		points.visible = path !== null;
		if ( ! path ) return;
		const geometry = points.geometry;
		options.time = time;
		options.alpha = alpha;
		options.count = count;
		const dots = layoutFlow( path, options, geometry.attributes.position.array, geometry.attributes.color.array, 0, 4, 3 );
		geometry.setDrawRange( 0, dots );
		geometry.attributes.position.needsUpdate = true;
		geometry.attributes.color.needsUpdate = true;

	}

	/** What window.glasshead.cues reports. */
	state() {

		const c = this.cues;
		return {
			visible: c.visible, voicing: c.voicing, nasal: c.nasal, oral: c.oral,
			turbulence: this.shown.turbulence,
			voicingShown: this.voicing.visible,
			// The aerodynamics behind it: areas mm², flows cm³/s, the noise in dB re a voiceless /s/.
			air: {
				glottisMm2: round2( this.air.glottisMm2 ), oralAreaMm2: round2( this.air.areaMm2 ),
				oralFlow: round2( this.air.oral ), nasalFlow: round2( this.air.nasal ),
				noiseDb: Number.isFinite( this.air.levelDb ) ? round2( this.air.levelDb ) : null,
			},
			nasalStrength: Math.round( this.shown.nasalStrength * 1000 ) / 1000,
			oralStopped: this.shown.oralStopped,
			oralStopMm: round2( this.shown.oralStopMm ),
			oralReachMm: round2( this.shown.oralReachMm ),
			oralFrontX: round2( this.shown.oralFrontX ),
		};

	}

	dispose() {

		this.group.removeFromParent();
		for ( const points of [ this.oral, this.nasal, this.swirl ] ) {

			points.geometry.dispose();
			points.material.dispose();

		}

		for ( const ring of this.rings ) ring.material.dispose();
		this.ringGeometry.dispose();
		this.glowGeometry.dispose();
		this.glow.material.dispose();
		this.texture.dispose();

	}

}

const round2 = ( v ) => ( v === null ? null : Math.round( v * 100 ) / 100 );

/** The largest x of a drawn dot (alpha above 0) of a flow's points, mm, or null. */
function frontX( geometry ) {

	const p = geometry.attributes.position.array, a = geometry.attributes.color.array;
	let front = null;
	for ( let k = 0; k < geometry.drawRange.count; k ++ ) if ( a[ 4 * k + 3 ] > 0 && ( front === null || p[ 3 * k ] > front ) ) front = p[ 3 * k ];
	return front;

}

/** A cue's material: transparent, over everything, not writing depth. */
function cueMaterial( material ) {

	material.transparent = true;
	material.depthTest = false;
	material.depthWrite = false;
	return material;

}

/** A soft round dot (white, its alpha falling off from the centre), for particles and the glow. */
function dotTexture() {

	const size = 64;
	const canvas = document.createElement( 'canvas' );
	canvas.width = canvas.height = size;
	const ctx = canvas.getContext( '2d' );
	const gradient = ctx.createRadialGradient( size / 2, size / 2, 0, size / 2, size / 2, size / 2 );
	gradient.addColorStop( 0, 'rgba(255,255,255,1)' );
	gradient.addColorStop( 0.55, 'rgba(255,255,255,0.95)' );
	gradient.addColorStop( 1, 'rgba(255,255,255,0)' );
	ctx.fillStyle = gradient;
	ctx.fillRect( 0, 0, size, size );
	return new CanvasTexture( canvas );

}
