// What the child's practice says when something is wrong, as a picture and words that the voice
// says aloud (a child may not read): a class code that cannot be one, and what to do about it.
// Pure: ChildPracticeSignIn.js shows them, tests/js/childPractice.test.js reads them.

import { JOIN_CODE_PATTERN, normaliseJoinCode } from './ChildPracticeFlow.js';

/** Letters and numbers a class code never has (docs/lessons.md): look-alikes of others. */
const NEVER_IN_A_CODE = '0O1IL2Z5S8B';

/** A list read aloud: 'B', 'B and 1', 'B, 1 and 2'. */
function spoken( items ) {

	return items.length > 1 ? `${ items.slice( 0, - 1 ).join( ', ' ) } and ${ items.at( - 1 ) }` : items[ 0 ];

}

/**
 * What is wrong with a typed class code, as { text, icon } to show and say, or null when it can
 * be a code. Spaces and dashes are fine (they are dropped); a letter codes never have, or the
 * wrong number of them, is said with what to do.
 */
export function codeMessage( typed ) {

	const code = normaliseJoinCode( typed );
	if ( code === '' ) return { text: 'Type the class code: six letters and numbers.', icon: 'ask-adult' };
	const never = [ ...new Set( [ ...code ].filter( ( c ) => NEVER_IN_A_CODE.includes( c ) ) ) ];
	if ( never.length ) return { text: `A class code never has ${ spoken( never ) }. Ask a grown-up to read the code again.`, icon: 'ask-adult' };
	const odd = [ ...new Set( [ ...code ].filter( ( c ) => ! /[A-Z0-9]/.test( c ) ) ) ];
	if ( odd.length ) return { text: `A class code has only letters and numbers, not ${ spoken( odd ) }. Ask a grown-up to read the code again.`, icon: 'ask-adult' };
	if ( code.length !== 6 ) return { text: `A class code has 6 letters and numbers; this one has ${ code.length }. Ask a grown-up to check it.`, icon: 'ask-adult' };
	return JOIN_CODE_PATTERN.test( code ) ? null : { text: 'Ask a grown-up to check the class code.', icon: 'ask-adult' };

}

/** No class has this code. */
export const NO_CLASS = Object.freeze( { text: 'There is no class with this code. Ask a grown-up to check it.', icon: 'ask-adult' } );
