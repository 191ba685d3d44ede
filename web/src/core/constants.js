// Project-wide constants, mirrored from server/glasshead/constants.py.
// tests/vectors/constants.json holds the Python values; tests/js/constants.test.js checks them.

/** Units of every length in the project frame. */
export const FRAME_UNITS = 'mm';

/** +x anterior, +y superior, +z toward the subject's left; z = 0 is the mid-sagittal plane. */
export const FRAME_AXES = Object.freeze( { x: 'anterior', y: 'superior', z: 'left' } );

// --- Electropalatography (the Reading 62-electrode palate) ---------------------------------------
// A frame is 64 bytes, row-major: row 0 = R1 (front, alveolar) ... row 7 = R8 (back, velar);
// column 0 = electrode column 1 ... column 7 = column 8. R1 has no electrode in columns 1 and 8.

/** Rows and columns of the EPG grid. */
export const EPG_ROWS = 8;
export const EPG_COLUMNS = 8;
/** Cells per frame in the flat layout (row-major, R1 first): 8 * 8. */
export const EPG_CELLS = EPG_ROWS * EPG_COLUMNS;
/** Electrodes on the palate: 8 * 8 minus the two missing corners of R1. */
export const EPG_ELECTRODES = EPG_CELLS - 2;
/** Flat cell indices (row * 8 + column) that have no electrode: R1 columns 1 and 8. */
export const EPG_MISSING_CELLS = Object.freeze( [ 0, 7 ] );
/** Zones as half-open row ranges: alveolar R1-R2, palatal R3-R5, velar R6-R8. */
export const EPG_ZONES = Object.freeze( {
	alveolar: Object.freeze( [ 0, 2 ] ),
	palatal: Object.freeze( [ 2, 5 ] ),
	velar: Object.freeze( [ 5, 8 ] ),
} );
