// Project-wide constants: the frame, grid sizes, tolerances and table formats. They are written
// once, in server/glasshead/constants.py, and generated into shared.generated.js (its header says
// how to regenerate it); kernels and views import them from here. tests/vectors/constants.json
// holds the Python values and tests/js/constants.test.js checks them.
//
// The EPG frame: 64 bytes, row-major: row 0 = R1 (front, alveolar) ... row 7 = R8 (back, velar);
// column 0 = electrode column 1 ... column 7 = column 8. R1 has no electrode in columns 1 and 8.

export * from './shared.generated.js';
