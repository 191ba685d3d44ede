// A QR code as an SVG element built with the DOM (the page's policy allows no inline markup or
// styles): the modules of uqr's encoding, one path of unit squares, black on a white quiet zone.
//
//   element.append( qrSvg( 'http://school.example/#/practice?code=ACD347', { label: 'Join link' } ) );

import { encode } from 'uqr';

const SVG = 'http://www.w3.org/2000/svg';

/** The modules of `text` as rows of booleans (true: dark), with a quiet zone of `border` modules. */
export function qrModules( text, { border = 4 } = {} ) {

	return encode( text, { ecc: 'M', border } ).data;

}

/** The SVG path of the dark modules: a run of dark modules in a row is one rectangle. */
export function qrPath( modules ) {

	const parts = [];
	modules.forEach( ( row, y ) => {

		let x = 0;
		while ( x < row.length ) {

			if ( ! row[ x ] ) {

				x += 1;
				continue;

			}

			const start = x;
			while ( x < row.length && row[ x ] ) x += 1;
			parts.push( `M${ start } ${ y }h${ x - start }v1h${ start - x }z` );

		}

	} );
	return parts.join( '' );

}

/** An <svg> of the QR code of `text`, named `label` for a screen reader. */
export function qrSvg( text, { label = text, document = globalThis.document } = {} ) {

	const modules = qrModules( text );
	const size = modules.length;
	const svg = document.createElementNS( SVG, 'svg' );
	svg.setAttribute( 'viewBox', `0 0 ${ size } ${ size }` );
	svg.setAttribute( 'role', 'img' );
	svg.setAttribute( 'aria-label', label );
	svg.setAttribute( 'shape-rendering', 'crispEdges' );
	const background = document.createElementNS( SVG, 'rect' );
	background.setAttribute( 'width', String( size ) );
	background.setAttribute( 'height', String( size ) );
	background.setAttribute( 'fill', '#ffffff' );
	const dark = document.createElementNS( SVG, 'path' );
	dark.setAttribute( 'd', qrPath( modules ) );
	dark.setAttribute( 'fill', '#000000' );
	svg.append( background, dark );
	return svg;

}
