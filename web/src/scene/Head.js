// The head: the anatomy meshes, their materials, the skin transparency and the sagittal cutaway.
//
// Every mesh sits in its own Group (`head.part( name ).group`) so that others can move it (the jaw
// rotates about a lateral axis) or swap its geometry (`setGeometry`, for the parametric tongue),
// and its section outline moves with it.

import {
	BackSide,
	DoubleSide,
	Box3,
	FrontSide,
	Group,
	LessEqualDepth,
	Mesh,
	MeshBasicMaterial,
	Plane,
	Vector3,
} from 'three';
import { createTissueMaterial, tissueOf, TISSUE_COLORS } from './materials.js';
import { LIP_RENDER_ORDER, lipOpacity, SKIN_RENDER_ORDER, skinPassState } from './skinPasses.js';
import { SectionOutline } from './SectionOutline.js';
import { SectionCap } from './SectionCap.js';
import { colorJawVertices, lowestY } from './jawColors.js';
import { weldNormals } from '../core/weldNormals.js';
import { buildOpeningMeshes } from './FaceOpenings.js';

/** Clipping plane offset that keeps everything (cutaway off) without recompiling shaders. */
const NO_CUT = 1e6;

/** Skin vertices closer than this (mm) are the same point of the seam. */
const WELD_TOLERANCE_MM = 0.01;

/** Depth bias of the skin passes (glPolygonOffset factor and units). */
const SKIN_DEPTH_BIAS = Object.freeze( { factor: 1, units: 2 } );

/** Tissues whose meshes are open surfaces (not watertight); drawn two-sided. */
const OPEN_TISSUES = new Set( [ 'maxilla', 'bone' ] );

/** Closed tissues whose cut gets a cap on the plane (SectionCap), and their cut colours. The tongue
 * and the lips are pressed against the teeth, which would show through their sections otherwise. */
const CAPPED_TISSUES = Object.freeze( { tongue: TISSUE_COLORS.tongueCut, lip: TISSUE_COLORS.lipCut } );

/** Render order of the first cap: after the opaque anatomy, before the section outlines (5). */
const CAP_RENDER_ORDER = 1;

export class Head {

	constructor() {

		this.group = new Group();
		this.group.name = 'head';
		this.parts = new Map();
		this.transparency = 0;
		this.cutaway = false;
		// Keeps z >= 0 (the subject's left half) when its constant is 0.
		this.clipPlane = new Plane( new Vector3( 0, 0, 1 ), NO_CUT );
		this.skinMaterials = null;

	}

	/**
	 * Add one anatomy mesh. entry: { name, role, ... } from GET /anatomy; geometry: an indexed or
	 * plain BufferGeometry in the project frame (mm).
	 */
	addPart( entry, geometry ) {

		if ( this.parts.has( entry.name ) ) throw new Error( `mesh "${ entry.name }" is already loaded` );
		if ( ! geometry.getAttribute( 'normal' ) ) geometry.computeVertexNormals();

		const tissue = tissueOf( entry );
		const group = new Group();
		group.name = entry.name;
		const part = { name: entry.name, role: entry.role ?? null, tissue, group, geometry, meshes: [], outline: null };

		if ( tissue === 'skin' ) {

			this.addSkinPasses( part );

		} else {

			const material = createTissueMaterial( tissue, { closed: ! OPEN_TISSUES.has( tissue ) } );
			// Two-sided always: a closed mesh's back faces only show through the cut, as its section.
			material.side = DoubleSide;
			material.clippingPlanes = [ this.clipPlane ];
			const mesh = new Mesh( geometry, material );
			mesh.name = entry.name;
			part.meshes.push( mesh );
			group.add( mesh );

		}

		if ( tissue in CAPPED_TISSUES ) {

			const capped = [ ...this.parts.values() ].filter( ( other ) => other.cap ).length;
			part.cap = new SectionCap( geometry, this.clipPlane, CAPPED_TISSUES[ tissue ], CAP_RENDER_ORDER + capped );
			group.add( ...part.cap.meshes );

		}

		part.outline = new SectionOutline( geometry );
		part.outline.visible = this.cutaway;
		group.add( part.outline );

		this.parts.set( entry.name, part );
		this.group.add( group );
		this.applyState();
		return part;

	}

	/** The skin is drawn in three ordered passes (see skinPasses.js); materials shared by all skin parts. */
	addSkinPasses( part ) {

		if ( ! this.skinMaterials ) {

			const back = createTissueMaterial( 'skin' );
			back.side = BackSide;
			const front = createTissueMaterial( 'skin' );
			front.side = FrontSide;
			front.depthFunc = LessEqualDepth;
			const prepass = new MeshBasicMaterial( { colorWrite: false, transparent: true, side: FrontSide } );
			for ( const material of [ back, front, prepass ] ) {

				material.clippingPlanes = [ this.clipPlane ];
				// Where the lips and other anatomy touch the skin, their surfaces nearly coincide; a
				// small depth bias lets the anatomy win instead of flickering through the skin.
				material.polygonOffset = true;
				material.polygonOffsetFactor = SKIN_DEPTH_BIAS.factor;
				material.polygonOffsetUnits = SKIN_DEPTH_BIAS.units;

			}

			// The inside of the skin is background: pushed further back than its outside.
			back.polygonOffsetFactor = 2 * SKIN_DEPTH_BIAS.factor;
			back.polygonOffsetUnits = 4 * SKIN_DEPTH_BIAS.units;
			this.skinMaterials = { back, front, prepass };

		}

		for ( const pass of [ 'back', 'prepass', 'front' ] ) {

			const mesh = new Mesh( part.geometry, this.skinMaterials[ pass ] );
			mesh.name = `${ part.name }:${ pass }`;
			mesh.userData.skinPass = pass;
			part.meshes.push( mesh );
			part.group.add( mesh );

		}

		for ( const mesh of buildOpeningMeshes( part.geometry ) ) {

			mesh.material.clippingPlanes = [ this.clipPlane ];
			part.meshes.push( mesh );
			part.group.add( mesh );

		}

	}

	/**
	 * Call once every part is added: colours the jaws (the mandible's teeth are found from the
	 * maxilla's occlusal level) and welds the skin seams.
	 */
	finishLoading() {

		const maxilla = [ ...this.parts.values() ].find( ( part ) => part.tissue === 'maxilla' );
		const occlusalY = maxilla ? lowestY( maxilla.geometry ) : undefined;
		for ( const part of this.parts.values() ) {

			if ( part.tissue === 'maxilla' ) part.dental = colorJawVertices( part.geometry, 'maxilla' );
			if ( part.tissue === 'mandible' ) {

				if ( occlusalY === undefined ) {

					// Without an upper jaw there is no occlusal level: plain bone.
					part.meshes[ 0 ].material.vertexColors = false;
					part.meshes[ 0 ].material.color.set( TISSUE_COLORS.bone );

				} else part.dental = colorJawVertices( part.geometry, 'mandible', { occlusalY } );

			}

		}

		this.weldSkinSeams();

	}

	/**
	 * Smooths the shading across the seam of the skin parts
	 * (face_skin and head_shell share their rim vertices). Returns the number of welded vertices.
	 */
	weldSkinSeams() {

		const skins = [ ...this.parts.values() ].filter( ( part ) => part.tissue === 'skin' );
		if ( skins.length < 2 ) return 0;
		const meshes = skins.map( ( part ) => ( {
			positions: part.geometry.getAttribute( 'position' ).array,
			normals: part.geometry.getAttribute( 'normal' ).array,
		} ) );
		const welded = weldNormals( meshes, WELD_TOLERANCE_MM );
		for ( const part of skins ) part.geometry.getAttribute( 'normal' ).needsUpdate = true;
		return welded;

	}

	/** The part called `name`, or undefined. */
	part( name ) {

		return this.parts.get( name );

	}

	/** Replace a part's geometry (e.g. a deformed tongue) and its section outline. */
	setGeometry( name, geometry ) {

		const part = this.parts.get( name );
		if ( ! part ) throw new Error( `no mesh called "${ name }"` );
		if ( ! geometry.getAttribute( 'normal' ) ) geometry.computeVertexNormals();
		part.geometry = geometry;
		for ( const mesh of part.meshes ) mesh.geometry = geometry;
		part.cap?.setGeometry( geometry );
		part.outline.update( geometry );

	}

	/**
	 * Move the vertices of part `name` to `positions` (Float32Array, 3 per vertex, same count and
	 * triangles as before), e.g. a deformed tongue each frame. Normals and the section outline
	 * follow; nothing is allocated once the outline buffer is large enough.
	 */
	updateVertices( name, positions ) {

		const part = this.parts.get( name );
		if ( ! part ) throw new Error( `no mesh called "${ name }"` );
		const attribute = part.geometry.getAttribute( 'position' );
		if ( positions.length !== attribute.array.length ) {

			throw new RangeError( `"${ name }" has ${ attribute.count } vertices; got ${ positions.length / 3 }` );

		}

		attribute.array.set( positions );
		attribute.needsUpdate = true;
		part.geometry.computeVertexNormals();
		part.geometry.computeBoundingSphere(); // reuses its Sphere: no allocation
		if ( this.cutaway ) part.outline.update( part.geometry );
		else part.outlineStale = true;

	}

	/** Skin transparency in percent, 0 (opaque) to 100 (no skin). */
	setTransparency( percent ) {

		skinPassState( percent ); // validates
		this.transparency = percent;
		this.applyState();

	}

	/** Sagittal cutaway: keep the subject's left half (z >= 0) when on. */
	setCutaway( on ) {

		this.cutaway = Boolean( on );
		this.applyState();

	}

	applyState() {

		const state = skinPassState( this.transparency );
		this.clipPlane.constant = this.cutaway ? 0 : NO_CUT;

		if ( this.skinMaterials ) {

			const { back, front } = this.skinMaterials;
			for ( const material of [ back, front ] ) {

				material.transparent = state.transparent;
				material.opacity = state.opacity;
				material.depthWrite = state.depthWrite;
				material.userData.section.rim.value = state.rim;
				material.needsUpdate = true; // `transparent` changes the shader's OPAQUE define

			}

			// The inside of the skin: the cut tissue when cut away; a dark cavity behind the eye and
			// nostril openings when the skin is opaque; shaded as skin when seen through the skin.
			const inside = back.userData.section;
			inside.rim.value = 0;
			inside.sectionOn.value = this.cutaway || ! state.transparent ? 1 : 0;
			inside.sectionColor.value.set( this.cutaway ? TISSUE_COLORS.skinCut : TISSUE_COLORS.skinCavity );

		}

		for ( const part of this.parts.values() ) {

			if ( this.cutaway && part.outlineStale ) {

				part.outline.update( part.geometry );
				part.outlineStale = false;

			}

			part.outline.visible = this.cutaway;
			// Faded lips are seen through anyway; their cut stays as faded as they are.
			part.cap?.setVisible( this.cutaway && ( part.tissue !== 'lip' || lipOpacity( this.transparency ) === 1 ) );
			for ( const mesh of part.meshes ) {

				const pass = mesh.userData.skinPass;
				if ( mesh.userData.opening ) {

					// Eyes and nostrils belong to the skin: they fade and disappear with it.
					const material = mesh.material;
					if ( material.transparent !== state.transparent ) {

						material.transparent = state.transparent;
						material.needsUpdate = true;

					}

					material.opacity = state.opacity;
					material.depthWrite = state.depthWrite;
					material.userData.section.sectionOn.value = this.cutaway ? 1 : 0;
					mesh.renderOrder = SKIN_RENDER_ORDER.front;
					mesh.visible = state.visible;

				} else if ( pass ) {

					mesh.renderOrder = SKIN_RENDER_ORDER[ pass ];
					if ( pass === 'back' ) mesh.visible = state.visible;
					else if ( pass === 'prepass' ) mesh.visible = state.prepass;
					else mesh.visible = state.visible;

				} else {

					if ( part.tissue === 'lip' ) {

						const opacity = lipOpacity( this.transparency );
						mesh.material.opacity = opacity;
						if ( mesh.material.transparent !== opacity < 1 ) {

							mesh.material.transparent = opacity < 1;
							mesh.material.needsUpdate = true;

						}

						mesh.renderOrder = opacity < 1 ? LIP_RENDER_ORDER : 0;
						// Faded lips show only their outer surface (their inside would add clutter),
						// unless the cut needs the inside to draw the section.
						mesh.material.side = opacity < 1 && ! this.cutaway ? FrontSide : DoubleSide;

					}

					const sectionable = mesh.material.userData.sectionable;
					mesh.material.userData.section.sectionOn.value = this.cutaway && sectionable ? 1 : 0;

				}

			}

		}

	}

	/** Bounding box of the anatomy meshes (world frame; section outlines excluded). */
	boundingBox( target = new Box3() ) {

		target.makeEmpty();
		for ( const part of this.parts.values() ) {

			part.geometry.computeBoundingBox();
			target.union( part.geometry.boundingBox.clone().applyMatrix4( part.group.matrixWorld ) );

		}

		return target;

	}

	/** World box around the lips (the mouth), falling back to the frame origin, which is in the mouth. */
	mouthBox( target = new Box3() ) {

		target.makeEmpty();
		for ( const name of [ 'upper_lip', 'lower_lip' ] ) {

			const part = this.parts.get( name );
			if ( ! part ) continue;
			part.geometry.computeBoundingBox();
			target.union( part.geometry.boundingBox.clone().applyMatrix4( part.group.matrixWorld ) );

		}

		if ( target.isEmpty() ) target.setFromCenterAndSize( new Vector3( 20, - 5, 0 ), new Vector3( 40, 40, 50 ) );
		return target;

	}

	/** [{ name, triangles }] of the loaded meshes, in loading order. */
	meshInfo() {

		return Array.from( this.parts.values(), ( part ) => ( { name: part.name, triangles: triangleCount( part.geometry ) } ) );

	}

	dispose() {

		for ( const part of this.parts.values() ) {

			part.geometry.dispose();
			for ( const mesh of part.meshes ) {

				if ( mesh.userData.skinPass ) continue;
				mesh.material.dispose();
				if ( mesh.geometry !== part.geometry ) mesh.geometry.dispose();

			}

			part.outline.geometry.dispose();
			part.cap?.dispose();

		}

		if ( this.skinMaterials ) for ( const material of Object.values( this.skinMaterials ) ) material.dispose();
		this.group.removeFromParent();
		this.parts.clear();

	}

}

/** Triangles drawn by a BufferGeometry. */
export function triangleCount( geometry ) {

	return geometry.index ? geometry.index.count / 3 : geometry.getAttribute( 'position' ).count / 3;

}
