// EPG contact indices per frame, exactly as the emuR package computes them.
//
// Source: emuR, R/epg.class.R (Harrington et al.): epgsum, epgcog, epgai, epgci, epgdi, with their
// default arguments. Formulae: Hardcastle, Gibbon & Nicolaidis (1991), J. Phonetics 19, 251-266
// (percent contact, centre of gravity); Fontdevila, Pallarès & Recasens (1994), J. Phonetics 22,
// 141-154 (contact indices); Recasens & Pallarès (2001), J. Phonetics 29, 273-301, p. 283 (the
// weights of the anteriority, centrality and dorsopalatal indices).
//
// Twin of server/glasshead/epg/indices.py; tests/vectors/epg-indices.json (real frames of the
// emuR engassim set) is checked by both.
//
// Frames are flat Uint8Arrays of 64 contacts (0/1) per frame, row-major: row 0 = R1 (front),
// column 0 = electrode column 1. The R1 corners (cells 0 and 7) have no electrode and hold 0.

import { EPG_CELLS, EPG_COLUMNS, EPG_ELECTRODES, EPG_MISSING_CELLS, EPG_ROWS, EPG_ZONES } from './constants.js';

/** Names of the values written per frame, in target order (same as INDEX_SLOTS in Python). */
export const INDEX_SLOTS = Object.freeze( [
	'contacts', 'percent',
	'row1', 'row2', 'row3', 'row4', 'row5', 'row6', 'row7', 'row8',
	'alveolar', 'palatal', 'velar',
	'alveolar_percent', 'palatal_percent', 'velar_percent',
	'cog', 'anteriority', 'centrality', 'dorsopalatal',
] );
/** Float64 values written per frame: 2 + 8 rows + 3 zones + 3 zone percents + 4 indices. */
export const INDEX_STRIDE = 2 + EPG_ROWS + 3 + 3 + 4;

/** Offsets within one frame's values. */
export const SLOT_CONTACTS = 0;
export const SLOT_PERCENT = 1;
export const SLOT_ROW1 = 2;
export const SLOT_ALVEOLAR = SLOT_ROW1 + EPG_ROWS;
export const SLOT_ALVEOLAR_PERCENT = SLOT_ALVEOLAR + 3;
export const SLOT_COG = SLOT_ALVEOLAR_PERCENT + 3;
export const SLOT_ANTERIORITY = SLOT_COG + 1;
export const SLOT_CENTRALITY = SLOT_COG + 2;
export const SLOT_DORSOPALATAL = SLOT_COG + 3;

/** Electrodes in a zone of EPG_ZONES: its cells less the missing ones (alveolar 6 + 8, else 3 * 8). */
function zoneElectrodes( [ first, end ] ) {

	const missing = EPG_MISSING_CELLS.filter( ( cell ) => cell >= first * EPG_COLUMNS && cell < end * EPG_COLUMNS ).length;
	return ( end - first ) * EPG_COLUMNS - missing;

}

const ALVEOLAR_ELECTRODES = zoneElectrodes( EPG_ZONES.alveolar );
const PALATAL_ELECTRODES = zoneElectrodes( EPG_ZONES.palatal );
const VELAR_ELECTRODES = zoneElectrodes( EPG_ZONES.velar );

/** epgai weights of rows R1..R5 over their electrode counts; 4921 = round(9^4 * 6/8). */
const AI_R1 = 4921 / 6, AI_R2 = 729 / 8, AI_R3 = 81 / 8, AI_R4 = 9 / 8, AI_R5 = 1 / 8;
const AI_LOG_TOTAL = Math.log( 1 + 4921 + 729 + 81 + 9 + 1 );
/** epgci weights of column pairs (1,8), (2,7), (3,6), (4,5) over their electrode counts. */
const CI_18 = 1 / 14, CI_27 = 17 / 16, CI_36 = 289 / 16, CI_45 = 4913 / 16;
const CI_LOG_TOTAL = Math.log( 1 + 1 + 17 + 289 + 4913 );

/**
 * Indices of one frame, written into target[ targetOffset ... targetOffset + INDEX_STRIDE ).
 * Allocates nothing.
 * @param {Uint8Array} frames 64 contacts per frame
 * @param {number} frameIndex which frame
 * @param {Float64Array} target receives INDEX_STRIDE values in INDEX_SLOTS order
 * @param {number} [targetOffset=0]
 * @returns {Float64Array} target
 */
export function epgIndices( frames, frameIndex, target, targetOffset = 0 ) {

	const base = frameIndex * EPG_CELLS;
	let total = 0, cogSum = 0;
	let outer = 0, second = 0, third = 0, central = 0;
	for ( let r = 0; r < EPG_ROWS; r ++ ) {

		const o = base + r * EPG_COLUMNS;
		const c1 = frames[ o ], c2 = frames[ o + 1 ], c3 = frames[ o + 2 ], c4 = frames[ o + 3 ];
		const c5 = frames[ o + 4 ], c6 = frames[ o + 5 ], c7 = frames[ o + 6 ], c8 = frames[ o + 7 ];
		const rowSum = c1 + c2 + c3 + c4 + c5 + c6 + c7 + c8;
		target[ targetOffset + SLOT_ROW1 + r ] = rowSum;
		total += rowSum;
		cogSum += rowSum * ( 7.5 - r ); // epgcog weights 7.5 (R1) ... 0.5 (R8)
		outer += c1 + c8;
		second += c2 + c7;
		third += c3 + c6;
		central += c4 + c5;

	}

	const t = targetOffset;
	const row = t + SLOT_ROW1;
	const r1 = target[ row ], r2 = target[ row + 1 ], r3 = target[ row + 2 ], r4 = target[ row + 3 ];
	const r5 = target[ row + 4 ], r6 = target[ row + 5 ], r7 = target[ row + 6 ], r8 = target[ row + 7 ];
	const alveolar = r1 + r2, palatal = r3 + r4 + r5, velar = r6 + r7 + r8;

	target[ t + SLOT_CONTACTS ] = total;
	target[ t + SLOT_PERCENT ] = 100 * total / EPG_ELECTRODES;
	target[ t + SLOT_ALVEOLAR ] = alveolar;
	target[ t + SLOT_ALVEOLAR + 1 ] = palatal;
	target[ t + SLOT_ALVEOLAR + 2 ] = velar;
	target[ t + SLOT_ALVEOLAR_PERCENT ] = 100 * alveolar / ALVEOLAR_ELECTRODES;
	target[ t + SLOT_ALVEOLAR_PERCENT + 1 ] = 100 * palatal / PALATAL_ELECTRODES;
	target[ t + SLOT_ALVEOLAR_PERCENT + 2 ] = 100 * velar / VELAR_ELECTRODES;
	target[ t + SLOT_COG ] = total > 0 ? cogSum / total : 0;
	target[ t + SLOT_ANTERIORITY ] =
		Math.log( 1 + AI_R1 * r1 + AI_R2 * r2 + AI_R3 * r3 + AI_R4 * r4 + AI_R5 * r5 ) / AI_LOG_TOTAL;
	target[ t + SLOT_CENTRALITY ] =
		Math.log( 1 + CI_18 * outer + CI_27 * second + CI_36 * third + CI_45 * central ) / CI_LOG_TOTAL;
	target[ t + SLOT_DORSOPALATAL ] = velar / VELAR_ELECTRODES;
	return target;

}

/**
 * Indices of every frame: target holds frameCount * INDEX_STRIDE values, frame after frame.
 * @param {Uint8Array} frames 64 contacts per frame
 * @param {number} frameCount
 * @param {Float64Array} target
 * @returns {Float64Array} target
 */
export function epgIndicesAll( frames, frameCount, target ) {

	if ( frames.length < frameCount * EPG_CELLS ) throw new RangeError( `epgIndicesAll: ${frameCount} frames need ${frameCount * EPG_CELLS} contacts, got ${frames.length}` );
	if ( target.length < frameCount * INDEX_STRIDE ) throw new RangeError( `epgIndicesAll: target needs ${frameCount * INDEX_STRIDE} values, got ${target.length}` );
	for ( let i = 0; i < frameCount; i ++ ) epgIndices( frames, i, target, i * INDEX_STRIDE );
	return target;

}

/**
 * Reads emuR-style row strings (8 strings of '0'/'1', R1 first) into frames at frameIndex.
 * @param {string[]} rows
 * @param {Uint8Array} frames
 * @param {number} frameIndex
 * @returns {Uint8Array} frames
 */
export function rowsToFrame( rows, frames, frameIndex ) {

	if ( rows.length !== EPG_ROWS ) throw new RangeError( `rowsToFrame: expected ${EPG_ROWS} rows, got ${rows.length}` );
	const base = frameIndex * EPG_CELLS;
	for ( let r = 0; r < EPG_ROWS; r ++ ) {

		const row = rows[ r ];
		if ( row.length !== EPG_COLUMNS ) throw new RangeError( `rowsToFrame: row ${r + 1} has ${row.length} contacts, not ${EPG_COLUMNS}` );
		for ( let c = 0; c < EPG_COLUMNS; c ++ ) {

			const ch = row.charCodeAt( c ) - 48;
			if ( ch !== 0 && ch !== 1 ) throw new RangeError( `rowsToFrame: row ${r + 1} column ${c + 1} is '${row[ c ]}', not 0 or 1` );
			frames[ base + r * EPG_COLUMNS + c ] = ch;

		}

	}

	return frames;

}
