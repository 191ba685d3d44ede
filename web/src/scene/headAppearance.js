// How the head's parts look: which materials each tissue gets, and what the skin transparency and
// the sagittal cutaway do to them (Head.applyState calls the two apply functions after every
// change). The decisions:
//   - the skin is drawn in three ordered passes (skinPasses.js) that fade it and finally hide it,
//     with its eye and nostril openings fading along;
//   - the lips fade with the skin (keeping 1 - LIP_FADE of their opacity when it is gone), showing
//     only their outer surface when faded (unless the cut needs their inside for the section);
//   - with the cut, every sectionable material shows its section colour, the inside of the skin
//     shows the cut skin (a dark cavity behind the openings when the skin is opaque), and the
//     closed tissues pressed against the teeth (tongue, lips) get a cap on the cutting plane.

import { BackSide, DoubleSide, FrontSide, LessEqualDepth, MeshBasicMaterial } from 'three';
import { createTissueMaterial, TISSUE_COLORS } from './materials.js';
import { LIP_RENDER_ORDER, lipOpacity, SKIN_RENDER_ORDER } from './skinPasses.js';

/** Depth bias of the skin passes (glPolygonOffset factor and units). */
const SKIN_DEPTH_BIAS = Object.freeze( { factor: 1, units: 2 } );

/** Tissues whose meshes are open surfaces (not watertight); drawn two-sided. */
const OPEN_TISSUES = new Set( [ 'maxilla', 'bone', 'mucosa', 'cartilage' ] );

/** Closed tissues whose cut gets a cap on the plane (SectionCap), and their cut colours. The tongue
 * and the lips are pressed against the teeth, which would show through their sections otherwise;
 * every cap also covers the cutaway's air (AirLayer.js), which is drawn before them. */
export const CAPPED_TISSUES = Object.freeze( {
	tongue: TISSUE_COLORS.tongueCut,
	lip: TISSUE_COLORS.lipCut,
	velum: TISSUE_COLORS.velumCut,
	solidBone: TISSUE_COLORS.boneCut,
	cartilage: TISSUE_COLORS.cartilageCut,
} );

/** Parts that lie in the neck, below the head: there is no neck skin to cover them, so they are
 * shown only when the inside is (skin see-through or cut away), never hanging under an opaque head. */
export const NECK_PARTS = Object.freeze( new Set( [ 'vertebrae', 'thyroid', 'cricoid', 'arytenoid_left', 'arytenoid_right', 'hyoid' ] ) );

/** Whether part `name` is drawn at this skin transparency (percent) and cut. */
export function partShown( name, transparency, cutaway ) {

	return ! NECK_PARTS.has( name ) || cutaway || transparency > 0;

}

/** Render order of the first cap: after the opaque anatomy, before the section outlines (5). */
const CAP_RENDER_ORDER = 1;

/** Render order of the cap of the `capped`-th capped part (0 first). */
export function capRenderOrder( capped ) {

	return CAP_RENDER_ORDER + capped;

}

/** The material of a part that is not skin, clipped by `clipPlane`. */
export function createPartMaterial( tissue, clipPlane ) {

	const material = createTissueMaterial( tissue, { closed: ! OPEN_TISSUES.has( tissue ) } );
	// Two-sided always: a closed mesh's back faces only show through the cut, as its section.
	material.side = DoubleSide;
	material.clippingPlanes = [ clipPlane ];
	return material;

}

/** A mandible without an upper jaw has no occlusal level to find its teeth from: plain bone. */
export function plainBone( material ) {

	material.vertexColors = false;
	material.color.set( TISSUE_COLORS.bone );

}

/** The three skin pass materials { back, front, prepass }, shared by every skin part. */
export function createSkinMaterials( clipPlane ) {

	const back = createTissueMaterial( 'skin' );
	back.side = BackSide;
	const front = createTissueMaterial( 'skin' );
	front.side = FrontSide;
	front.depthFunc = LessEqualDepth;
	const prepass = new MeshBasicMaterial( { colorWrite: false, transparent: true, side: FrontSide } );
	for ( const material of [ back, front, prepass ] ) {

		material.clippingPlanes = [ clipPlane ];
		// Where the lips and other anatomy touch the skin, their surfaces nearly coincide; a
		// small depth bias lets the anatomy win instead of flickering through the skin.
		material.polygonOffset = true;
		material.polygonOffsetFactor = SKIN_DEPTH_BIAS.factor;
		material.polygonOffsetUnits = SKIN_DEPTH_BIAS.units;

	}

	// The inside of the skin is background: pushed further back than its outside.
	back.polygonOffsetFactor = 2 * SKIN_DEPTH_BIAS.factor;
	back.polygonOffsetUnits = 4 * SKIN_DEPTH_BIAS.units;
	return { back, front, prepass };

}

/**
 * The skin pass materials for a skinPassState() `state` and the cut.
 * @param {{ back: object, front: object }} materials from createSkinMaterials()
 */
export function applySkinAppearance( { back, front }, state, cutaway ) {

	for ( const material of [ back, front ] ) {

		material.transparent = state.transparent;
		material.opacity = state.opacity;
		material.depthWrite = state.depthWrite;
		material.userData.section.rim.value = state.rim;
		material.needsUpdate = true; // `transparent` changes the shader's OPAQUE define

	}

	// Without the cut, the front faces are the nearest skin wherever they are: the inside need not
	// write depth. When it did, it won against the front faces where they are seen edge-on (the
	// outline, the crease where the face meets the head shell) and showed there as dark speckles.
	back.depthWrite = state.depthWrite && cutaway;

	// The inside of the skin: the cut tissue when cut away; a dark cavity behind the eye and
	// nostril openings when the skin is opaque; shaded as skin when seen through the skin.
	const inside = back.userData.section;
	inside.rim.value = 0;
	inside.sectionOn.value = cutaway || ! state.transparent ? 1 : 0;
	inside.sectionColor.value.set( cutaway ? TISSUE_COLORS.skinCut : TISSUE_COLORS.skinCavity );

}

/**
 * One part of the head for a skinPassState() `state`, the skin transparency in percent and the
 * cut: its section outline and cap, and each of its meshes (skin passes, openings, lips, the rest).
 */
export function applyPartAppearance( part, state, transparency, cutaway ) {

	const shown = partShown( part.name, transparency, cutaway );
	part.outline.visible = cutaway && shown && part.tissue !== 'air';
	// Faded lips are seen through anyway; their cut stays as faded as they are.
	part.cap?.setVisible( cutaway && shown && ( part.tissue !== 'lip' || lipOpacity( transparency ) === 1 ) );
	for ( const mesh of part.meshes ) {

		const pass = mesh.userData.skinPass;
		if ( mesh.userData.opening ) applyOpening( mesh, state, cutaway );
		else if ( pass ) {

			mesh.renderOrder = SKIN_RENDER_ORDER[ pass ];
			mesh.visible = pass === 'prepass' ? state.prepass : state.visible;

		} else {

			mesh.visible = shown;
			if ( part.tissue === 'lip' ) applyLip( mesh, lipOpacity( transparency ), cutaway );
			const sectionable = mesh.material.userData.sectionable;
			mesh.material.userData.section.sectionOn.value = cutaway && sectionable ? 1 : 0;

		}

	}

}

/** Eyes and nostrils belong to the skin: they fade and disappear with it. */
function applyOpening( mesh, state, cutaway ) {

	const material = mesh.material;
	if ( material.transparent !== state.transparent ) {

		material.transparent = state.transparent;
		material.needsUpdate = true;

	}

	material.opacity = state.opacity;
	material.depthWrite = state.depthWrite;
	material.userData.section.sectionOn.value = cutaway ? 1 : 0;
	mesh.renderOrder = SKIN_RENDER_ORDER.front;
	mesh.visible = state.visible;

}

/** A lip at `opacity` (lipOpacity() of the skin transparency). */
function applyLip( mesh, opacity, cutaway ) {

	mesh.material.opacity = opacity;
	if ( mesh.material.transparent !== opacity < 1 ) {

		mesh.material.transparent = opacity < 1;
		mesh.material.needsUpdate = true;

	}

	// Opaque or not, after the markers drawn over the anatomy (the see-through electrodes, the
	// contacts), which must not show through the lips.
	mesh.renderOrder = LIP_RENDER_ORDER;
	// Faded lips show only their outer surface (their inside would add clutter), unless the cut
	// needs the inside to draw the section.
	mesh.material.side = opacity < 1 && ! cutaway ? FrontSide : DoubleSide;

}
