// What the clinician view says in words, pure: the indices' readable names with their units and
// direction, a recording's title from the meta its import kept (word, segment label, speaker), and
// the agreement of a frame in a form an empty palatogram cannot win (Cohen's kappa, computed by the
// compare API: server/glasshead/epg/compare.py) beside the raw share of electrodes.

/**
 * The indices of the table, in its order: a readable name with the unit and what its ends mean
 * (emuR's definitions, web/src/core/epgIndices.js). The centre of gravity weighs R1 as 7.5 and R8
 * as 0.5, so a larger value is further forward.
 */
export const INDEX_LABELS = Object.freeze( {
	percent: 'Contact (% of the 62 electrodes)',
	cog: 'Centre of gravity (rows: 0.5 = back R8 … 7.5 = front R1)',
	anteriority: 'Anteriority (0 = no front contact … 1 = front rows)',
	centrality: 'Centrality (0 = sides only … 1 = midline)',
	dorsopalatal: 'Dorsopalatal (share of R6–R8 on, 0 … 1)',
	alveolar_percent: 'Alveolar contact (% of R1–R2)',
	palatal_percent: 'Palatal contact (% of R3–R5)',
	velar_percent: 'Velar contact (% of R6–R8)',
} );

/** The table's difference column: which side is subtracted (the compare API's convention). */
export const DIFFERENCE_HEADING = 'recording − target';

/** One line under the agreement card: what kappa says that the raw share does not. */
export const AGREEMENT_EXPLANATION = 'κ (Cohen\'s kappa): agreement beyond chance, 1 = identical, 0 = no better than chance (an empty palatogram scores 0). Raw: share of the 62 electrodes on or off in both.';

/** A readable name of an index (its code name when it has none). */
export function indexLabel( name ) {

	return INDEX_LABELS[ name ] ?? name;

}

/**
 * The speaker of a recording from its utterance ('sp1bescan' with the word 'bescan' -> 'sp1'): what
 * comes before the word, else a leading letters-and-digits code; null when neither is there.
 */
export function speakerOf( meta ) {

	const utterance = typeof meta?.utterance === 'string' ? meta.utterance : '';
	const word = typeof meta?.word === 'string' ? meta.word : '';
	if ( word && utterance.length > word.length && utterance.endsWith( word ) ) return utterance.slice( 0, - word.length );
	return /^([a-z]+\d+)/i.exec( utterance )?.[ 1 ] ?? null;

}

/**
 * The title of a recording for a person: 'bescan (s→k), speaker sp1' from its meta (word, segment
 * label, speaker), else its name.
 * @param {{ name: string, meta?: { word?: string, label?: string, utterance?: string } }} recording
 */
export function recordingTitle( recording ) {

	const meta = recording.meta ?? {};
	const word = typeof meta.word === 'string' && meta.word.trim() ? meta.word.trim() : null;
	if ( ! word ) return recording.name;
	const label = typeof meta.label === 'string' && meta.label.trim() ? ` (${ meta.label.trim().replace( '->', '→' ) })` : '';
	const speaker = speakerOf( meta );
	return `${ word }${ label }${ speaker ? `, speaker ${ speaker }` : '' }`;

}

/**
 * The agreement card's caption at `frame`: kappa and the raw share, with the recording's means;
 * kappa is left out when the server gives none.
 */
export function agreementText( comparison, frame ) {

	const percent = ( value ) => `${ Math.round( value * 100 ) } %`;
	const kappa = ( value ) => ( Number.isFinite( value ) ? value.toFixed( 2 ).replace( '-', '−' ) : '–' );
	const raw = `raw ${ percent( comparison.agreement[ frame ] ) } (mean ${ percent( comparison.summary.mean_agreement ) })`;
	if ( ! comparison.kappa ) return raw;
	return `κ ${ kappa( comparison.kappa[ frame ] ) } (mean ${ kappa( comparison.summary.mean_kappa ) }) · ${ raw }`;

}

/**
 * Under the agreement card, for a target that says the recording's phones: kappa per phone over
 * its frames, and the mean over the phones (null when the comparison has no phones).
 */
export function phoneScoresText( comparison ) {

	const phones = comparison?.phones;
	if ( ! phones?.length ) return null;
	const kappa = ( value ) => ( Number.isFinite( value ) ? value.toFixed( 2 ).replace( '-', '−' ) : '–' );
	const each = phones.map( ( p ) => `/${ p.ipa ?? p.symbol }/ κ ${ kappa( p.mean_kappa ) } (${ p.frames } frames)` );
	return `Per phone: ${ each.join( ' · ' ) }; mean over the phones κ ${ kappa( comparison.summary.phones?.mean_kappa ) }`;

}
