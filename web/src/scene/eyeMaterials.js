// Materials of the eyes: an eyeball with a procedural iris and pupil, and a skin-coloured upper lid
// whose edge slides down to blink. Both get the section shading (materials.js) so that the skin's
// openings can switch them with the cut.

import { Color } from 'three';
import { createColorPatchedMaterial, TISSUE_COLORS } from './materials.js';
import { EYE_MOTION } from '../core/eyes.js';

/** Eye colours: a sclera that is not pure white, a grey-blue iris with a darker rim. */
export const EYE_COLORS = Object.freeze( {
	sclera: '#ece4da',
	iris: '#6d8595',
	irisInner: '#8a7a55',
	limbus: '#2c3a44',
	pupil: '#0d0d0f',
	lash: '#3a2a24',
} );

/** The eyeball's material (sphere of `radius` mm, its pole along +z in its own frame). */
export function createEyeballMaterial( radius ) {

	const uniforms = {};
	for ( const [ name, value ] of Object.entries( EYE_COLORS ) ) uniforms[ `uEye_${ name }` ] = { value: new Color( value ) };
	const mm = ( x ) => x.toFixed( 3 );
	return createColorPatchedMaterial( { color: '#ffffff', roughness: 0.16 }, { sectionColor: TISSUE_COLORS.skinCut }, {
		key: `glasshead-eyeball-${ radius }`,
		varyings: 'varying vec3 vEyeLocal;',
		vertex: 'vEyeLocal = position;',
		uniforms,
		declarations: `uniform vec3 ${ Object.keys( uniforms ).join( ', ' ) };`,
		color: `	vec3 d = normalize( vEyeLocal );
	float r = d.z > 0.0 ? length( d.xy ) * ${ mm( radius ) } : ${ mm( radius ) };
	float theta = atan( d.y, d.x );
	float edge = fwidth( r ) + 0.12;
	float irisR = ${ mm( EYE_MOTION.irisRadius ) }, pupilR = ${ mm( EYE_MOTION.pupilRadius ) };
	float t = clamp( ( r - pupilR ) / ( irisR - pupilR ), 0.0, 1.0 );
	// Radial fibres and a warmer collarette round the pupil.
	float fibres = 0.5 + 0.3 * sin( theta * 41.0 + 2.0 * sin( theta * 7.0 ) ) + 0.2 * sin( theta * 97.0 + r * 2.3 );
	vec3 iris = mix( uEye_irisInner, uEye_iris, smoothstep( 0.15, 0.45, t ) );
	iris *= 0.78 + 0.32 * fibres;
	iris = mix( iris, uEye_limbus, smoothstep( 0.72, 1.0, t ) );
	vec3 sclera = uEye_sclera * mix( 1.0, 0.8, smoothstep( 0.5, 1.0, r / ${ mm( radius ) } ) );
	vec3 eye = mix( iris, sclera, smoothstep( irisR - edge, irisR + edge, r ) );
	eye = mix( uEye_pupil, eye, smoothstep( pupilR - edge, pupilR + edge, r ) );
	diffuseColor.rgb *= eye;`,
	} );

}

/**
 * The upper lid's material: skin where the lid covers the opening, nothing below its edge. The
 * edge (in the lid's own height coordinate, 0 at the opening's bottom, 1 at its top) rests at
 * 1 - userData.lid.rest and moves to below the bottom as userData.lid.closure goes to 1.
 */
export function createLidMaterial() {

	const lid = { closure: { value: 0 }, rest: { value: 0 }, lash: { value: new Color( EYE_COLORS.lash ) } };
	const material = createColorPatchedMaterial( { color: TISSUE_COLORS.skin, roughness: 0.7 }, { sectionColor: TISSUE_COLORS.skinCut }, {
		key: 'glasshead-eyelid',
		attributes: 'attribute vec2 lidCoord;',
		varyings: 'varying vec2 vLidCoord;',
		vertex: 'vLidCoord = lidCoord;',
		uniforms: { uLidClosure: lid.closure, uLidRest: lid.rest, uLidLash: lid.lash },
		declarations: 'uniform float uLidClosure, uLidRest;\nuniform vec3 uLidLash;',
		color: `	// The edge arches: lowest in the middle of the opening.
	float edge = mix( 1.0 - uLidRest, -0.08, uLidClosure ) + 0.12 * vLidCoord.y * vLidCoord.y * ( 1.0 - uLidClosure );
	float above = vLidCoord.x - edge;
	if ( above < 0.0 ) discard;
	diffuseColor.rgb = mix( uLidLash, diffuseColor.rgb * 0.92, smoothstep( 0.0, 0.06, above ) );`,
	} );
	material.userData.lid = lid;
	return material;

}
