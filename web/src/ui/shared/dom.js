// Building the page's elements: h( tag, attributes, ...children ), the one helper every view and
// panel builds its DOM with.

/** Create an element with attributes and children. */
export function h( tag, attributes = {}, ...children ) {

	const element = document.createElement( tag );
	for ( const [ key, value ] of Object.entries( attributes ) ) {

		if ( key === 'className' ) element.className = value;
		else if ( key.startsWith( 'on' ) ) element.addEventListener( key.slice( 2 ).toLowerCase(), value );
		else element.setAttribute( key, value );

	}

	element.append( ...children );
	return element;

}
