// Materials that make the anatomy legible: one colour per tissue, a flat "cut tissue" colour on the
// faces seen through the cutaway, and a fresnel rim that keeps faint skin readable.

import { Color, DoubleSide, FrontSide, MeshStandardMaterial } from 'three';

/** Tissue colours (sRGB). Chosen to read on a projector: distinct hues, similar lightness. */
export const TISSUE_COLORS = Object.freeze( {
	skin: '#e2ad8f',
	skinCut: '#c9786c', // soft tissue under the skin, as seen in the section
	skinCavity: '#4a2f2c', // the inside of the head seen through the eye and nostril openings
	teeth: '#f6efd9', // ivory
	gum: '#e2878d', // gums and palate
	bone: '#d9c7a4',
	tongue: '#c0353f',
	tongueCut: '#97262f',
	lip: '#d46f7a',
	lipCut: '#ad4c58',
	air: '#b9def5', // the empty vocal tract in the cutaway: a light sky blue
	velum: '#d9707c', // the soft palate
	velumCut: '#b24f5c',
	mucosa: '#d98a86', // the posterior pharyngeal wall
	cartilage: '#c9dde3', // larynx cartilages: bluish white
	cartilageCut: '#9fbcc6',
	boneCut: '#c4ad80', // the cut of the hyoid, the spine and the occiput
	brain: '#a99bb4', // the cranial cavity in the cutaway: a muted lavender grey
	brainRim: '#6f6280', // where the cranium's band ends around it
} );

/** What each mesh is drawn as, by name first and by role if the name is new. */
const TISSUE_BY_NAME = Object.freeze( {
	face_skin: 'skin',
	head_shell: 'skin',
	maxilla: 'maxilla',
	mandible: 'mandible',
	tongue_rest: 'tongue',
	tongue: 'tongue',
	upper_lip: 'lip',
	lower_lip: 'lip',
	cranium: 'bone',
	airway: 'air',
	velum_rest: 'velum',
	pharynx: 'mucosa',
	hyoid: 'solidBone',
	vertebrae: 'solidBone',
} );

const TISSUE_BY_ROLE = Object.freeze( {
	skin: 'skin',
	shell: 'skin',
	maxilla: 'maxilla',
	mandible: 'mandible',
	jaw: 'mandible',
	tongue: 'tongue',
	lip: 'lip',
	lips: 'lip',
	bone: 'bone',
	cranium: 'bone',
	air: 'air',
	soft: 'mucosa',
	cartilage: 'cartilage',
} );

/**
 * The tissue kind of an anatomy entry: 'skin', 'maxilla', 'mandible', 'tongue', 'lip', 'bone'
 * (open bone surfaces: the cranium), 'solidBone' (closed bones: hyoid, spine), 'velum',
 * 'mucosa' (open soft surfaces: the pharyngeal wall), 'cartilage' or 'air' (the airway, drawn
 * only as the cutaway's air, scene/AirLayer.js).
 */
export function tissueOf( entry ) {

	return TISSUE_BY_NAME[ entry.name ] ?? TISSUE_BY_ROLE[ entry.role ] ?? 'bone';

}

/**
 * Patch a MeshStandardMaterial so that, when `uniforms.sectionOn` is 1, its back faces (the inside
 * of a clipped mesh, seen through the cut) are drawn unlit in a cut colour: a closed mesh then looks
 * filled, like a section through solid tissue. The cut colour is `sectionColor`, or the material's
 * own diffuse colour (vertex colours included) times `sectionShade` when `fromDiffuse` is set.
 * A fresnel rim of strength `rim` raises the opacity (and lightens the colour) at grazing angles.
 */
export function addSectionShading( material, { sectionColor = '#888888', fromDiffuse = false, sectionShade = 0.8, sectionable = true } = {} ) {

	const uniforms = {
		sectionOn: { value: 0 },
		sectionColor: { value: new Color( sectionColor ) },
		sectionFromDiffuse: { value: fromDiffuse ? 1 : 0 },
		sectionShade: { value: sectionShade },
		rim: { value: 0 },
		rimColor: { value: new Color( '#fff4ec' ) },
	};

	material.onBeforeCompile = ( shader ) => {

		shader.uniforms.uSectionOn = uniforms.sectionOn;
		shader.uniforms.uSectionColor = uniforms.sectionColor;
		shader.uniforms.uSectionFromDiffuse = uniforms.sectionFromDiffuse;
		shader.uniforms.uSectionShade = uniforms.sectionShade;
		shader.uniforms.uRim = uniforms.rim;
		shader.uniforms.uRimColor = uniforms.rimColor;
		shader.fragmentShader = shader.fragmentShader
			.replace( '#include <common>', `#include <common>
uniform float uSectionOn;
uniform vec3 uSectionColor;
uniform float uSectionFromDiffuse;
uniform float uSectionShade;
uniform float uRim;
uniform vec3 uRimColor;` )
			.replace( '#include <opaque_fragment>', `#include <opaque_fragment>
if ( uRim > 0.0 ) {
	float facing = abs( dot( normalize( normal ), normalize( vViewPosition ) ) );
	float rim = uRim * pow( 1.0 - facing, 2.5 );
	gl_FragColor.rgb = mix( gl_FragColor.rgb, uRimColor, rim * 0.6 );
	gl_FragColor.a += ( 1.0 - gl_FragColor.a ) * rim;
}
#ifdef FLIP_SIDED
bool seenFromInside = gl_FrontFacing; // a BackSide material draws only inner faces, flagged as front
#else
bool seenFromInside = ! gl_FrontFacing;
#endif
if ( uSectionOn > 0.5 && seenFromInside ) {
	gl_FragColor.rgb = mix( uSectionColor, diffuseColor.rgb * uSectionShade, uSectionFromDiffuse );
}` );

	};

	material.customProgramCacheKey = () => 'glasshead-section-shading';
	material.userData.section = uniforms;
	material.userData.sectionable = sectionable;
	return material;

}

/**
 * A new material for a tissue kind. Closed meshes are single-sided (their back faces only show
 * through the cut, where they are drawn as the section); open meshes are two-sided.
 * Returns the material; its section uniforms are in material.userData.section.
 */
export function createTissueMaterial( tissue, { closed = true } = {} ) {

	const common = { roughness: 0.62, metalness: 0, side: closed ? FrontSide : DoubleSide };
	switch ( tissue ) {

		case 'skin':
			return addSectionShading( new MeshStandardMaterial( { ...common, color: TISSUE_COLORS.skin, roughness: 0.7 } ), { sectionColor: TISSUE_COLORS.skinCut } );
		case 'tongue':
			return addSectionShading( new MeshStandardMaterial( { ...common, color: TISSUE_COLORS.tongue, roughness: 0.45 } ), { sectionColor: TISSUE_COLORS.tongueCut } );
		case 'lip':
			return addSectionShading( new MeshStandardMaterial( { ...common, color: TISSUE_COLORS.lip, roughness: 0.5 } ), { sectionColor: TISSUE_COLORS.lipCut } );
		case 'velum':
			return addSectionShading( new MeshStandardMaterial( { ...common, color: TISSUE_COLORS.velum, roughness: 0.5 } ), { sectionColor: TISSUE_COLORS.velumCut } );
		case 'mucosa':
			return addSectionShading( new MeshStandardMaterial( { ...common, color: TISSUE_COLORS.mucosa, roughness: 0.55 } ), { fromDiffuse: true, sectionShade: 0.8, sectionable: false } );
		case 'cartilage':
			return addSectionShading( new MeshStandardMaterial( { ...common, color: TISSUE_COLORS.cartilage, roughness: 0.4 } ), { sectionColor: TISSUE_COLORS.cartilageCut } );
		case 'solidBone':
			return addSectionShading( new MeshStandardMaterial( { ...common, color: TISSUE_COLORS.bone } ), { sectionColor: TISSUE_COLORS.boneCut } );
		case 'maxilla':
		case 'mandible':
			// White base colour: the per-vertex colours (teeth, gums, bone) give the hue.
			return addSectionShading( new MeshStandardMaterial( { ...common, color: '#ffffff', vertexColors: true, roughness: 0.5 } ), { fromDiffuse: true, sectionShade: 0.8 } );
		default:
			// Bone surfaces such as the cranium band are open: their inside is shown shaded, not as a cut.
			return addSectionShading( new MeshStandardMaterial( { ...common, color: TISSUE_COLORS.bone } ), { fromDiffuse: true, sectionShade: 0.8, sectionable: false } );

	}

}

/**
 * A section-shaded MeshStandardMaterial (addSectionShading, with `section`) whose diffuse colour
 * is then changed by GLSL of its own. `patch`: `attributes` and `varyings` (GLSL declarations;
 * the varyings in both stages), `vertex` (statements after begin_vertex that set the varyings),
 * `uniforms` ({ name: { value } }) with their GLSL `declarations`, `color` (statements after
 * color_fragment that change diffuseColor), and `key` naming the compiled program.
 */
export function createColorPatchedMaterial( parameters, section, { key, attributes = '', varyings, vertex, uniforms = {}, declarations = '', color } ) {

	const material = addSectionShading( new MeshStandardMaterial( parameters ), section );
	const sectionShading = material.onBeforeCompile;
	material.onBeforeCompile = ( shader, renderer ) => {

		sectionShading( shader, renderer );
		Object.assign( shader.uniforms, uniforms );
		shader.vertexShader = shader.vertexShader
			.replace( '#include <common>', `#include <common>\n${ attributes }\n${ varyings }` )
			.replace( '#include <begin_vertex>', `#include <begin_vertex>\n${ vertex }` );
		shader.fragmentShader = shader.fragmentShader
			.replace( '#include <common>', `#include <common>\n${ varyings }\n${ declarations }` )
			.replace( '#include <color_fragment>', `#include <color_fragment>\n{\n${ color }\n}` );

	};

	material.customProgramCacheKey = () => key;
	return material;

}
