// Project-wide constants, mirrored from server/glasshead/constants.py.
// tests/vectors/constants.json holds the Python values; tests/js/constants.test.js checks them.

/** Units of every length in the project frame. */
export const FRAME_UNITS = 'mm';

/** +x anterior, +y superior, +z toward the subject's left; z = 0 is the mid-sagittal plane. */
export const FRAME_AXES = Object.freeze( { x: 'anterior', y: 'superior', z: 'left' } );
