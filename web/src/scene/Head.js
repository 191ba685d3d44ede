// The head: the anatomy meshes, their materials, the skin transparency and the sagittal cutaway.
// How each part looks at a transparency and with or without the cut is headAppearance.js.
//
// Every mesh sits in its own Group (`head.part( name ).group`) so that others can move it (the jaw
// rotates about a lateral axis) or swap its geometry (`setGeometry`, for the parametric tongue),
// and its section outline moves with it.

import { Box3, Group, Mesh, Plane, Vector3 } from 'three';
import { tissueOf } from './materials.js';
import { skinPassState } from './skinPasses.js';
import { SectionOutline } from './SectionOutline.js';
import { SectionCap } from './SectionCap.js';
import { colorJawVertices, lowestY } from './jawColors.js';
import { weldNormals } from '../core/weldNormals.js';
import { buildOpeningMeshes } from './FaceOpenings.js';
import { AirLayer } from './AirLayer.js';
import { CranialLayer } from './CranialLayer.js';
import { applyPartAppearance, applySkinAppearance, CAPPED_TISSUES, capRenderOrder, createPartMaterial, createSkinMaterials, plainBone } from './headAppearance.js';

/** Clipping plane offset that keeps everything (cutaway off) without recompiling shaders. */
const NO_CUT = 1e6;

/** Skin vertices closer than this (mm) are the same point of the seam. */
const WELD_TOLERANCE_MM = 0.01;

/** `target` set to the world box around `parts` (null entries skipped); empty when there are none. */
function partsBox( parts, target ) {

	target.makeEmpty();
	for ( const part of parts ) {

		if ( ! part ) continue;
		part.geometry.computeBoundingBox();
		target.union( part.geometry.boundingBox.clone().applyMatrix4( part.group.matrixWorld ) );

	}

	return target;

}

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

		} else if ( tissue !== 'air' ) { // the airway is drawn only as the cutaway's air (finishLoading)

			const mesh = new Mesh( geometry, createPartMaterial( tissue, this.clipPlane ) );
			mesh.name = entry.name;
			part.meshes.push( mesh );
			group.add( mesh );

		}

		if ( tissue in CAPPED_TISSUES ) {

			const capped = [ ...this.parts.values() ].filter( ( other ) => other.cap ).length;
			part.cap = new SectionCap( geometry, this.clipPlane, CAPPED_TISSUES[ tissue ], capRenderOrder( capped ) );
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

		this.skinMaterials ??= createSkinMaterials( this.clipPlane );
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
					plainBone( part.meshes[ 0 ].material );

				} else part.dental = colorJawVertices( part.geometry, 'mandible', { occlusalY } );

			}

		}

		this.weldSkinSeams();
		this.addAirLayer();
		this.addCranialLayer();

	}

	/**
	 * The cutaway's air (AirLayer.js), when an airway is loaded: its cavity is the airway, the
	 * rest tongue and the rest velum as loaded, with the mandible's section kept clear.
	 */
	addAirLayer() {

		const airway = [ ...this.parts.values() ].find( ( part ) => part.tissue === 'air' );
		if ( ! airway ) return;
		const find = ( tissue ) => [ ...this.parts.values() ].find( ( part ) => part.tissue === tissue );
		const mandible = find( 'mandible' );
		this.air = new AirLayer( {
			airway: airway.geometry,
			plane: this.clipPlane,
			tongue: find( 'tongue' )?.geometry ?? null,
			velum: find( 'velum' )?.geometry ?? null,
			jaw: mandible?.group ?? null,
			eraser: mandible?.geometry ?? null,
		} ).attach( this.group );
		this.air.setVisible( this.cutaway );

	}

	/** The cutaway's cranial cavity (CranialLayer.js), bounded by the cranium, in its group. */
	addCranialLayer() {

		const cranium = this.parts.get( 'cranium' );
		if ( ! cranium ) return;
		this.cranial = new CranialLayer( cranium.geometry ).attach( cranium.group );
		this.cranial.setVisible( this.cutaway );

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

	/** Show the transparency and the cutaway on every part (the policy: headAppearance.js). */
	applyState() {

		const state = skinPassState( this.transparency );
		this.clipPlane.constant = this.cutaway ? 0 : NO_CUT;
		if ( this.skinMaterials ) applySkinAppearance( this.skinMaterials, state, this.cutaway );
		this.air?.setVisible( this.cutaway );
		this.cranial?.setVisible( this.cutaway );
		for ( const part of this.parts.values() ) {

			if ( this.cutaway && part.outlineStale ) {

				part.outline.update( part.geometry );
				part.outlineStale = false;

			}

			applyPartAppearance( part, state, this.transparency, this.cutaway );

		}

	}

	/** Bounding box of the anatomy meshes (world frame; section outlines excluded). */
	/** World-space points of the skin's surface (every `step`-th vertex of each skin part). */
	skinPoints( step = 4 ) {

		const points = [];
		for ( const part of this.parts.values() ) {

			if ( part.tissue !== 'skin' ) continue;
			const positions = part.geometry.getAttribute( 'position' );
			for ( let i = 0; i < positions.count; i += step ) points.push( new Vector3().fromBufferAttribute( positions, i ).applyMatrix4( part.group.matrixWorld ) );

		}

		return points;

	}

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

		partsBox( [ this.parts.get( 'upper_lip' ), this.parts.get( 'lower_lip' ) ], target );
		if ( target.isEmpty() ) target.setFromCenterAndSize( new Vector3( 20, - 5, 0 ), new Vector3( 40, 40, 50 ) );
		return target;

	}

	/**
	 * World box around the velum while the cutaway shows it in section, else null: with the lips,
	 * what panels over the view keep clear of when they can.
	 */
	velumBox( target = new Box3() ) {

		if ( ! this.cutaway ) return null;
		const velum = [ ...this.parts.values() ].filter( ( part ) => part.tissue === 'velum' && part.group.visible );
		return partsBox( velum, target ).isEmpty() ? null : target;

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
		this.air?.dispose();
		this.cranial?.dispose();
		this.group.removeFromParent();
		this.parts.clear();

	}

}

/** Triangles drawn by a BufferGeometry. */
export function triangleCount( geometry ) {

	return geometry.index ? geometry.index.count / 3 : geometry.getAttribute( 'position' ).count / 3;

}
