// Accessibility checks with axe-core (Deque's engine, run inside the page): the WCAG 2 A and AA
// rules on what is on screen. A violation is returned as one line naming the rule, its impact
// and the elements, so that an assertion shows what to fix.
//
//   assert.deepEqual( await axeViolations( page ), [] );
//   assert.deepEqual( await axeViolations( page, { include: '.signin-view' } ), [] );

import { readFileSync } from 'node:fs';
import { createRequire } from 'node:module';

const require = createRequire( import.meta.url );
/** axe-core's browser build, as npm installs it. */
export const AXE_SCRIPT = require.resolve( 'axe-core/axe.min.js' );
/** The rule sets checked: WCAG 2.0 and 2.1, levels A and AA. */
export const AXE_TAGS = Object.freeze( [ 'wcag2a', 'wcag2aa', 'wcag21a', 'wcag21aa' ] );

/** The violations of `page` (within `include`, a CSS selector, or the whole document) as lines. */
export async function axeViolations( page, { include = null, tags = AXE_TAGS } = {} ) {

	// Evaluated through the browser's debugging protocol: the app's Content-Security-Policy (no
	// inline scripts) refuses a script tag, and rightly so.
	if ( ! await page.evaluate( () => typeof window.axe === 'object' ) ) await page.evaluate( readFileSync( AXE_SCRIPT, 'utf8' ) );
	const violations = await page.evaluate( async ( [ context, runTags ] ) => {

		const result = await window.axe.run( context ?? document, { runOnly: { type: 'tag', values: runTags }, resultTypes: [ 'violations' ] } );
		return result.violations.map( ( v ) => ( { id: v.id, impact: v.impact, help: v.help, targets: v.nodes.map( ( node ) => node.target.join( ' ' ) ) } ) );

	}, [ include, [ ...tags ] ] );
	return violations.map( ( v ) => `${ v.id } (${ v.impact }): ${ v.help } at ${ v.targets.join( ', ' ) }` );

}
