// The listening kernels (web/src/core/listen/) on recordings: one JSON object per 10 ms hop per
// line, as the browser measures a microphone. Many files run in one process, one after another.
//
//   npm run measure -- FILE.wav [FILE2.wav ...] [--group child|woman|man]
//
// Every file is read and checked before anything is printed: a missing file, a file that is not
// a PCM or float WAV, or a bad option prints one line on stderr and exits with status 2.
import { readFileSync, statSync } from 'node:fs';
import { analyseSamples } from '../web/src/core/listen/analyse.js';
import { DEFAULT_GROUP, GROUPS } from '../web/src/core/listen/params.js';
import { parseWav } from '../web/src/core/listen/wav.js';

const HELP = `Usage: npm run measure -- FILE.wav [FILE2.wav ...] [--group child|woman|man]

Prints the listening measures of each recording, one JSON object per 10 ms hop per line:
  t             time of the hop's centre, s
  f0            fundamental frequency, Hz (YIN, tracked); null when unvoiced
  voiced        true or false
  intensity_db  dB re 2e-5 Pa, the samples taken as pascals (a full-scale sine reads 91 dB)
  formants      [F1, F2, F3, F4], Hz (Burg LPC as Praat's To Formant (burg)); null where missing
  bandwidths    [B1, B2, B3, B4], Hz
  centroid      spectral centre of gravity, Hz, 0 to Nyquist
  spread        spectral standard deviation, Hz
  skew          spectral skewness
  peak          frequency of the strongest spectral peak, Hz
  f3_minus_f2   F3 - F2, Hz
With more than one file, each line starts with "file": the path as given.
Frequencies are rounded to 0.1 Hz, intensities to 0.01 dB, skewness to 0.001.

Options:
  --group G   speaker group: child (pitch 150-500 Hz, formant ceiling 6500 Hz),
              woman (120-400 Hz, 5500 Hz) or man (60-250 Hz, 5000 Hz); default ${ DEFAULT_GROUP }
  --help      this text

WAV files: integer PCM (8, 16, 24, 32 bit) or float (32, 64 bit), any rate of 8 kHz or more,
several channels averaged. Exit status 2 for a bad option, a missing file or one that is not
such a WAV.`;

/** One line on stderr and status 2: the caller's mistake, not ours. */
function refuse( message ) {

	process.stderr.write( `measure: ${ message }\n` );
	process.exit( 2 );

}

function parseArguments( argv ) {

	const files = [];
	let group = DEFAULT_GROUP;
	for ( let i = 0; i < argv.length; i ++ ) {

		const arg = argv[ i ];
		if ( arg === '--help' || arg === '-h' ) {

			process.stdout.write( `${ HELP }\n` );
			process.exit( 0 );

		} else if ( arg === '--group' || arg.startsWith( '--group=' ) ) {

			group = arg === '--group' ? argv[ ++ i ] : arg.slice( '--group='.length );
			if ( ! Object.hasOwn( GROUPS, group ?? '' ) ) refuse( `--group must be one of ${ Object.keys( GROUPS ).join( ', ' ) }, not ${ group === undefined ? 'nothing' : `"${ group }"` }` );

		} else if ( arg.startsWith( '-' ) && arg !== '-' ) {

			refuse( `unknown option ${ arg } (see --help)` );

		} else files.push( arg );

	}

	if ( files.length === 0 ) refuse( 'no WAV file given (see --help)' );
	return { files, group };

}

/** The file's samples, or a refusal naming the file and what is wrong with it. */
function readRecording( file ) {

	let bytes;
	try {

		if ( ! statSync( file ).isFile() ) refuse( `${ file }: not a file` );
		bytes = readFileSync( file );

	} catch ( error ) {

		refuse( `${ file }: ${ error.code === 'ENOENT' ? 'no such file' : error.message }` );

	}

	try {

		const wav = parseWav( bytes );
		if ( ! Number.isInteger( wav.sampleRate ) || wav.sampleRate < 8000 ) refuse( `${ file }: sample rate ${ wav.sampleRate } Hz is below 8000 Hz` );
		return wav;

	} catch ( error ) {

		if ( error.name !== 'WavError' ) throw error;
		refuse( `${ file }: ${ error.message }` );

	}

}

const tenth = ( v ) => ( v === null ? null : Math.round( v * 10 ) / 10 );
const hundredth = ( v ) => ( v === null ? null : Math.round( v * 100 ) / 100 );
const thousandth = ( v ) => ( v === null ? null : Math.round( v * 1000 ) / 1000 );

/** A hop as printed: fixed key order, rounded. */
function line( hop, file ) {

	const out = file === null ? {} : { file };
	out.t = thousandth( hop.t );
	out.f0 = tenth( hop.f0 );
	out.voiced = hop.voiced;
	out.intensity_db = hundredth( hop.intensity_db );
	out.formants = hop.formants.map( tenth );
	out.bandwidths = hop.bandwidths.map( tenth );
	out.centroid = tenth( hop.centroid );
	out.spread = tenth( hop.spread );
	out.skew = thousandth( hop.skew );
	out.peak = tenth( hop.peak );
	out.f3_minus_f2 = tenth( hop.f3_minus_f2 );
	return JSON.stringify( out );

}

// A reader that stops early (`| head`) is not an error.
process.stdout.on( 'error', ( error ) => process.exit( error.code === 'EPIPE' ? 0 : 1 ) );

const { files, group } = parseArguments( process.argv.slice( 2 ) );
for ( const file of files ) readRecording( file );
const named = files.length > 1;
for ( const file of files ) {

	const { samples, sampleRate } = readRecording( file );
	const hops = analyseSamples( samples, sampleRate, { group } );
	process.stdout.write( hops.map( ( hop ) => line( hop, named ? file : null ) ).join( '\n' ) + ( hops.length ? '\n' : '' ) );

}
