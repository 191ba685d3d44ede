// What the child's practice says when something is wrong, as a picture and words that the voice
// says aloud (a child may not read): a class code that cannot be one, and what to do about it.
// Pure: ChildPracticeSignIn.js shows them, tests/js/childPractice.test.js reads them.

import { JOIN_CODE_ALPHABET, JOIN_CODE_LENGTH, normaliseJoinCode } from './ChildPracticeFlow.js';

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
	// Letters and numbers outside the alphabet: the look-alikes it leaves out.
	const never = [ ...new Set( [ ...code ].filter( ( c ) => /[A-Z0-9]/.test( c ) && ! JOIN_CODE_ALPHABET.includes( c ) ) ) ];
	if ( never.length ) return { text: `A class code never has ${ spoken( never ) }. Ask a grown-up to read the code again.`, icon: 'ask-adult' };
	const odd = [ ...new Set( [ ...code ].filter( ( c ) => ! /[A-Z0-9]/.test( c ) ) ) ];
	if ( odd.length ) return { text: `A class code has only letters and numbers, not ${ spoken( odd ) }. Ask a grown-up to read the code again.`, icon: 'ask-adult' };
	if ( code.length !== JOIN_CODE_LENGTH ) return { text: `A class code has ${ JOIN_CODE_LENGTH } letters and numbers; this one has ${ code.length }. Ask a grown-up to check it.`, icon: 'ask-adult' };
	return null; // every character is of the alphabet, and there are six

}

/** No class has this code. */
export const NO_CLASS = Object.freeze( { text: 'There is no class with this code. Ask a grown-up to check it.', icon: 'ask-adult' } );
