// The pure parts of the listening displays: where a vowel's formants sit on the chart, the norm
// ellipses, which vowel a measurement is nearest and how near, where a fricative's centroid sits
// between /ʃ/ and /s/, and what the input's level says (silent, clipping, a whisper). The
// displays (VowelChart.js, SibilantMeter.js, TraceStrip.js) and the unit tests read these.

/** The built vowel norms (glasshead.pipeline.vowel_norms), from the site's root. */
export const NORMS_URL = '/assets/build/vowel-norms.json';

/** The chart's ranges, Hz: F1 down the side, F2 across (high F2, front vowels, on the left). */
export const CHART_F1_HZ = Object.freeze( [ 200, 1300 ] );
export const CHART_F2_HZ = Object.freeze( [ 600, 4200 ] );

/**
 * Mahalanobis distances (in log formant space, against a vowel's norm of the learner's group)
 * that count as in the target and as near it: 2.45 standard deviations hold 95 % of a group's
 * tokens of a vowel (chi-square, 2 degrees of freedom), 3.5 hold 99.8 %.
 */
export const IN_TARGET = 2.45;
export const NEAR_TARGET = 3.5;
/** The other vowels' ellipses are drawn at one standard deviation, so that they stay apart. */
export const NORM_OUTLINE = 1;

/**
 * The band the fricative's spectral moments are read in, Hz: the same on every device (a 16 kHz
 * recording reaches 8 kHz, a microphone at 48 kHz far beyond), above the room's rumble.
 */
export const SIBILANT_BAND_HZ = Object.freeze( [ 1000, 8000 ] );

/** SIBILANT_BAND_HZ within what a sample rate holds (an 8 kHz input reaches 4 kHz). */
export function sibilantBand( sampleRate ) {

	return [ SIBILANT_BAND_HZ[ 0 ], Math.min( SIBILANT_BAND_HZ[ 1 ], sampleRate / 2 ) ];

}

/**
 * Fricative centroids (in SIBILANT_BAND_HZ) of /ʃ/ and /s/ by speaker group, Hz: the meter's
 * two ends. /ʃ/'s front cavity is longer, so its energy sits lower; children's smaller mouths
 * put both higher. Adults after Jongman et al. (2000); children's from speechocean762's 6 to 8
 * year olds in this band (a sentence with /s/ and no /ʃ/ about 5,700 Hz, /ʃ/ words 4,200 to
 * 4,900 Hz with their stops).
 */
export const SIBILANT_ENDS_HZ = Object.freeze( {
	man: Object.freeze( { sh: 3300, s: 5500 } ),
	woman: Object.freeze( { sh: 3600, s: 5800 } ),
	child: Object.freeze( { sh: 4000, s: 6000 } ),
} );

/**
 * Where the F3 target line starts for /r/, by group, Hz (the learner's clinician moves it): an
 * /r/ brings F3 down towards F2, to about 1,600 to 1,800 Hz for men, 1,900 to 2,100 for women
 * and 2,200 to 2,500 for children (Hagiwara 1995; Flipsen et al. 2001), against about 2,500,
 * 2,900 and 3,300 in their other vowels.
 */
export const F3_TARGET_HZ = Object.freeze( { man: 1900, woman: 2200, child: 2600 } );

/** Intensity (dB re full scale) below which the input is taken as silence. */
export const SILENT_DB = - 55;
/**
 * A room is too noisy to measure a voice in when its quiet (the 10th percentile of the last
 * seconds' hops) is loud, more than NOISY_FLOOR_BELOW_FULL_SCALE_DB under full scale, and the
 * voice (the 90th percentile) stands less than NOISY_CONTRAST_DB over it. Loud speech with short
 * gaps has a loud 10th percentile too (a looped "heed": -32 dB), but stands 22 dB over it.
 */
export const NOISY_FLOOR_BELOW_FULL_SCALE_DB = 45;
export const NOISY_CONTRAST_DB = 20;

/** 'noisy' for such a room (`hops`' intensity_db, re 2e-5 Pa with full scale at `fullScaleDb`), else null. */
export function roomProblem( hops, fullScaleDb ) {

	const levels = hops.map( ( hop ) => hop.intensity_db ).filter( Number.isFinite ).sort( ( a, b ) => a - b );
	if ( levels.length < 100 ) return null;
	const quiet = levels[ Math.floor( levels.length / 10 ) ];
	const voice = levels[ Math.floor( levels.length * 9 / 10 ) ];
	return quiet > fullScaleDb - NOISY_FLOOR_BELOW_FULL_SCALE_DB && voice - quiet < NOISY_CONTRAST_DB ? 'noisy' : null;

}

/** A sample this close to full scale counts as clipped; this share of clipped samples is too loud. */
export const CLIP_LEVEL = 0.99;
export const CLIP_SHARE = 0.002;

const logRange = ( [ lo, hi ] ) => Math.log( hi ) - Math.log( lo );

/** The chart position { x, y } of (F1, F2) in a box { width, height, pad } (CSS pixels). */
export function chartPoint( f1, f2, { width, height, pad = 24 } ) {

	const u = ( Math.log( CHART_F2_HZ[ 1 ] ) - Math.log( f2 ) ) / logRange( CHART_F2_HZ );
	const v = ( Math.log( f1 ) - Math.log( CHART_F1_HZ[ 0 ] ) ) / logRange( CHART_F1_HZ );
	return { x: pad + u * ( width - 2 * pad ), y: pad + v * ( height - 2 * pad ) };

}

/**
 * The outline of a norm's ellipse at `scale` standard deviations: `count` points [F1, F2] (Hz)
 * around the mean of log (F1, F2) with covariance `cov` (vowel-norms.json's `log_f1_f2`).
 */
export function ellipse( { mean, cov }, scale = IN_TARGET, count = 48 ) {

	// The covariance's square root by its eigenvectors (a 2 x 2 symmetric matrix).
	const [ [ a, b ], [ , d ] ] = cov;
	const half = ( a + d ) / 2;
	const root = Math.sqrt( Math.max( 0, half * half - ( a * d - b * b ) ) );
	const l1 = half + root;
	const l2 = Math.max( 0, half - root );
	const angle = Math.abs( b ) > 1e-15 ? Math.atan2( l1 - a, b ) : ( a >= d ? 0 : Math.PI / 2 );
	const [ c, s ] = [ Math.cos( angle ), Math.sin( angle ) ];
	const points = [];
	for ( let k = 0; k < count; k ++ ) {

		const t = ( 2 * Math.PI * k ) / count;
		const p = scale * Math.sqrt( l1 ) * Math.cos( t );
		const q = scale * Math.sqrt( l2 ) * Math.sin( t );
		points.push( [ Math.exp( mean[ 0 ] + c * p - s * q ), Math.exp( mean[ 1 ] + s * p + c * q ) ] );

	}

	return points;

}

/** The Mahalanobis distance of (F1, F2) from a norm { mean, cov } of log (F1, F2). */
export function normDistance( f1, f2, { mean, cov } ) {

	const x = Math.log( f1 ) - mean[ 0 ];
	const y = Math.log( f2 ) - mean[ 1 ];
	const [ [ a, b ], [ , d ] ] = cov;
	const det = a * d - b * b;
	return Math.sqrt( Math.max( 0, ( d * x * x - 2 * b * x * y + a * y * y ) / det ) );

}

/**
 * The vowel of `vowels` ({ code: entry } of one group in vowel-norms.json) nearest (F1, F2):
 * { vowel, distance, zone } with zone 'in', 'near' or 'off'; null without a measurement.
 */
export function nearestVowel( f1, f2, vowels ) {

	if ( ! ( f1 > 0 && f2 > 0 ) ) return null;
	let best = null;
	for ( const [ vowel, entry ] of Object.entries( vowels ) ) {

		const distance = normDistance( f1, f2, entry.log_f1_f2 );
		if ( ! best || distance < best.distance ) best = { vowel, distance };

	}

	return best && { ...best, zone: zoneOf( best.distance ) };

}

/** 'in', 'near' or 'off' for a Mahalanobis distance. */
export function zoneOf( distance ) {

	return distance <= IN_TARGET ? 'in' : distance <= NEAR_TARGET ? 'near' : 'off';

}

/** Where `centroid` (Hz) sits on the meter of `group`: 0 at /ʃ/'s end, 1 at /s/'s, clamped. */
export function sibilantPosition( centroid, group = 'woman' ) {

	const ends = SIBILANT_ENDS_HZ[ group ] ?? SIBILANT_ENDS_HZ.woman;
	return Math.min( 1, Math.max( 0, ( centroid - ends.sh ) / ( ends.s - ends.sh ) ) );

}

/**
 * What a block of input says about the microphone: 'clipping' when too many samples reach full
 * scale, 'silent' when its intensity stays below SILENT_DB, else null. `samples`: Float32Array.
 */
export function inputProblem( samples ) {

	if ( ! samples.length ) return 'silent';
	let clipped = 0;
	let energy = 0;
	for ( let i = 0; i < samples.length; i ++ ) {

		const x = samples[ i ];
		if ( Math.abs( x ) >= CLIP_LEVEL ) clipped ++;
		energy += x * x;

	}

	if ( clipped / samples.length > CLIP_SHARE ) return 'clipping';
	const db = 10 * Math.log10( energy / samples.length + 1e-20 );
	return db < SILENT_DB ? 'silent' : null;

}

/** The median of `values` (numbers; left unsorted). */
export function median( values ) {

	const sorted = [ ...values ].sort( ( a, b ) => a - b );
	const mid = sorted.length >> 1;
	return sorted.length % 2 ? sorted[ mid ] : ( sorted[ mid - 1 ] + sorted[ mid ] ) / 2;

}

/** A voiced hop this far below the loudest of its run is a consonant's voicing, not the vowel's, dB. */
export const NUCLEUS_BELOW_PEAK_DB = 10;

/** Loudness above which an unvoiced hop counts as a fricative rather than the room, dB below the loudest hop. */
export const FRICATIVE_BELOW_PEAK_DB = 25;

/**
 * What an attempt (its hops, in time order) measured: the vowel as the median F0 and F1 to F3
 * over the middle half of the loud part (within NUCLEUS_BELOW_PEAK_DB of its peak) of its
 * longest voiced run: where a vowel holds steady, away from the consonants' transitions, and the fricative as the median centroid of its unvoiced hops
 * within FRICATIVE_BELOW_PEAK_DB of its loudest. { vowel: { f0, f1, f2, f3, f3_minus_f2,
 * duration_s } | null, fricative: { centroid, duration_s } | null }.
 */
export function summariseAttempt( hops ) {

	let best = [ 0, 0 ];
	let start = - 1;
	hops.forEach( ( hop, k ) => {

		const voiced = hop.voiced && hop.formants?.[ 0 ] > 0 && hop.formants?.[ 1 ] > 0;
		if ( voiced && start < 0 ) start = k;
		if ( ( ! voiced || k === hops.length - 1 ) && start >= 0 ) {

			const end = voiced ? k + 1 : k;
			if ( end - start > best[ 1 ] - best[ 0 ] ) best = [ start, end ];
			start = - 1;

		}

	} );
	// The vowel's nucleus: the loud part of the run, not the voicing of a closure after it.
	const voicedRun = hops.slice( best[ 0 ], best[ 1 ] );
	const loudest = Math.max( ...voicedRun.map( ( h ) => h.intensity_db ?? - Infinity ) );
	const loud = voicedRun.map( ( h ) => h.intensity_db >= loudest - NUCLEUS_BELOW_PEAK_DB );
	const run = voicedRun.slice( loud.indexOf( true ), loud.lastIndexOf( true ) + 1 );
	const middle = run.slice( Math.floor( run.length / 4 ), Math.max( Math.ceil( run.length * 3 / 4 ), Math.floor( run.length / 4 ) + 1 ) );
	const pick = ( read ) => {

		const values = middle.map( read ).filter( ( v ) => v > 0 );
		return values.length ? median( values ) : null;

	};

	const vowel = run.length < 3 ? null : {
		f0: pick( ( h ) => h.f0 ), f1: pick( ( h ) => h.formants[ 0 ] ), f2: pick( ( h ) => h.formants[ 1 ] ),
		f3: pick( ( h ) => h.formants[ 2 ] ), f3_minus_f2: pick( ( h ) => h.f3_minus_f2 ),
		duration_s: run.length && run.at( - 1 ).t - run[ 0 ].t,
	};
	const peak = Math.max( ...hops.map( ( h ) => ( Number.isFinite( h.intensity_db ) ? h.intensity_db : - Infinity ) ) );
	const hiss = hops.filter( ( h ) => ! h.voiced && h.centroid > 0 && h.intensity_db >= peak - FRICATIVE_BELOW_PEAK_DB );
	const fricative = hiss.length < 3 ? null : { centroid: median( hiss.map( ( h ) => h.centroid ) ), duration_s: hiss.length * ( hops[ 1 ]?.t - hops[ 0 ]?.t || 0.01 ) };
	return { vowel, fricative };

}

/** Where the fricative's centroid must sit on the meter to be in (or near) an /s/ or /ʃ/ target. */
export const SIBILANT_IN = 0.6;
export const SIBILANT_NEAR = 0.45;

/**
 * What a lesson item's target can be measured against: { kind: 'vowel', code } for a vowel of
 * the group's norms (by IPA or ARPAbet symbol), { kind: 'sibilant', sound: 's' | 'sh' } for /s/
 * or /ʃ/, null for anything else (words and phrases, other consonants).
 */
export function measurableTarget( target, vowels = {} ) {

	if ( target?.kind !== 'phoneme' ) return null;
	const text = String( target.text );
	if ( text === 's' || text.toUpperCase() === 'S' ) return { kind: 'sibilant', sound: 's' };
	if ( text === 'ʃ' || text.toUpperCase() === 'SH' ) return { kind: 'sibilant', sound: 'sh' };
	for ( const [ code, entry ] of Object.entries( vowels ) ) {

		if ( entry.ipa === text || entry.arpabet === text.toUpperCase() ) return { kind: 'vowel', code };

	}

	return null;

}

/**
 * What a lesson item is measured on: its own `listen` (the lesson schema's: a vowel with the
 * zone's edge in standard deviations, /s/ or /ʃ/ with where the zone starts on the meter, or
 * /r/ with the F3 to fall below), else what its phoneme target can be (measurableTarget).
 */
export function itemTarget( item, vowels = {} ) {

	const listen = item?.listen;
	if ( listen?.measure === 'vowel' ) return { kind: 'vowel', code: listen.vowel, withinSd: listen.within_sd ?? IN_TARGET };
	if ( listen?.measure === 'sibilant' ) return { kind: 'sibilant', sound: listen.sound, fromShare: listen.from_share ?? SIBILANT_IN };
	if ( listen?.measure === 'rhotic' ) return { kind: 'rhotic', f3BelowHz: listen.f3_below_hz ?? F3_TARGET_HZ.child };
	return measurableTarget( item?.target, vowels );

}

/** How much further than the target zone's edge counts as near: 1 sd, 15 % of the meter, 10 % of F3. */
const NEAR_SD = 1.05;
const NEAR_SHARE = SIBILANT_IN - SIBILANT_NEAR;
const NEAR_F3 = 1.1;

/**
 * The verdict on an attempt's summary (summariseAttempt) against a target (itemTarget):
 * 'in', 'near' or 'off', or null when the attempt gave nothing to judge (no vowel, no hiss).
 */
export function attemptZone( summary, target, vowels = {}, group = 'child' ) {

	if ( target?.kind === 'vowel' ) {

		const vowel = summary?.vowel;
		const norm = vowels[ target.code ];
		if ( ! vowel?.f1 || ! vowel?.f2 || ! norm ) return null;
		const edge = target.withinSd ?? IN_TARGET;
		const distance = normDistance( vowel.f1, vowel.f2, norm.log_f1_f2 );
		return distance <= edge ? 'in' : distance <= edge + NEAR_SD ? 'near' : 'off';

	}

	if ( target?.kind === 'sibilant' ) {

		const centroid = summary?.fricative?.centroid;
		if ( ! ( centroid > 0 ) ) return null;
		const position = sibilantPosition( centroid, group );
		const towards = target.sound === 's' ? position : 1 - position;
		const from = target.fromShare ?? SIBILANT_IN;
		return towards >= from ? 'in' : towards >= from - NEAR_SHARE ? 'near' : 'off';

	}

	if ( target?.kind === 'rhotic' ) {

		const f3 = summary?.vowel?.f3;
		if ( ! ( f3 > 0 ) ) return null;
		return f3 <= target.f3BelowHz ? 'in' : f3 <= target.f3BelowHz * NEAR_F3 ? 'near' : 'off';

	}

	return null;

}

/** The practice record's `measures` of an attempt: its numbers, rounded, and the verdict. */
export function attemptMeasures( summary, zone, target ) {

	const round = ( v, places = 1 ) => ( Number.isFinite( v ) && v > 0 ? Number( v.toFixed( places ) ) : null );
	const vowel = summary?.vowel ?? {};
	const measures = {
		f0: round( vowel.f0 ), f1: round( vowel.f1 ), f2: round( vowel.f2 ), f3: round( vowel.f3 ),
		f3_minus_f2: round( vowel.f3_minus_f2 ), centroid: round( summary?.fricative?.centroid ),
		duration_s: round( vowel.duration_s ?? summary?.fricative?.duration_s, 3 ), verdict: zone ?? null,
		target_vowel: target?.kind === 'vowel' ? target.code : null,
	};
	return Object.fromEntries( Object.entries( measures ).filter( ( [ , v ] ) => v !== null ) );

}

/** An attempt's summary in words, for the clinician's panel: 'vowel: F0 251 Hz, F1 410 Hz, …'. */
export function attemptWords( summary ) {

	const hz = ( v ) => ( v > 0 ? `${ Math.round( v ) } Hz` : '–' );
	const parts = [];
	const vowel = summary?.vowel;
	if ( vowel ) parts.push( `vowel: F0 ${ hz( vowel.f0 ) }, F1 ${ hz( vowel.f1 ) }, F2 ${ hz( vowel.f2 ) }, F3 ${ hz( vowel.f3 ) }, F3 − F2 ${ hz( vowel.f3_minus_f2 ) }, ${ vowel.duration_s.toFixed( 2 ) } s` );
	if ( summary?.fricative ) parts.push( `hiss: centroid ${ hz( summary.fricative.centroid ) }, ${ summary.fricative.duration_s.toFixed( 2 ) } s` );
	return parts.length ? parts.join( '; ' ) : 'Nothing measured: no voice and no hiss.';

}
