// The tracks of an EMA recording beside the head's (the clinician's EMA card), pure: for each
// sensor the head's height over time, and under it the speaker's, on one scale; the phones along
// the top; the frame shown as a line across. Drawing goes through an injected canvas 2D context,
// so it runs (and is tested) in Node with a recording context.

/** The sensors drawn, top to bottom, with their words. */
export const TRACK_SENSORS = Object.freeze( [
	Object.freeze( { name: 'tongue_tip', label: 'tongue tip' } ),
	Object.freeze( { name: 'tongue_blade', label: 'tongue blade' } ),
	Object.freeze( { name: 'tongue_dorsum', label: 'tongue dorsum' } ),
	Object.freeze( { name: 'lower_incisor', label: 'jaw (lower incisor)' } ),
	Object.freeze( { name: 'upper_lip', label: 'upper lip' } ),
	Object.freeze( { name: 'lower_lip', label: 'lower lip' } ),
] );

export const TRACK_COLORS = Object.freeze( {
	background: '#ffffff',
	ink: '#1f2328',
	muted: '#5f6770',
	grid: '#e3e0dc',
	head: '#b06000',
	speaker: '#1559a8',
	speech: 'rgba(21, 89, 168, 0.06)',
	cursor: '#1f2328',
} );

/** Heights of the parts, CSS pixels: the phones' row, one strip, the gap after each sensor. */
export const TRACK_LAYOUT = Object.freeze( { phones: 22, strip: 20, gap: 8, left: 118, right: 8 } );

/** The canvas height that shows every sensor's two strips. */
export function tracksHeight() {

	return TRACK_LAYOUT.phones + TRACK_SENSORS.length * ( 2 * TRACK_LAYOUT.strip + TRACK_LAYOUT.gap );

}

/** [min, max] of the vertical (y) values of both tracks of a sensor, NaN and null left out. */
export function heightRange( head, measured ) {

	let low = Infinity;
	let high = - Infinity;
	for ( const track of [ head, measured ] ) {

		for ( const point of track ?? [] ) {

			const y = point?.[ 1 ];
			if ( y === null || y === undefined || ! Number.isFinite( y ) ) continue;
			low = Math.min( low, y );
			high = Math.max( high, y );

		}

	}

	if ( ! Number.isFinite( low ) ) return [ 0, 1 ];
	if ( high - low < 1 ) return [ ( low + high ) / 2 - 0.5, ( low + high ) / 2 + 0.5 ];
	return [ low, high ];

}

/**
 * Draw `doc` (POST /ema/playback's answer) at frame `frame` on `ctx`, `width` CSS pixels wide.
 * Returns what was drawn, for tests: { sensors, cursorX }.
 */
export function drawEmaTracks( ctx, doc, frame, { width, height = tracksHeight() } ) {

	const { phones: phonesRow, strip, gap, left, right } = TRACK_LAYOUT;
	ctx.fillStyle = TRACK_COLORS.background;
	ctx.fillRect( 0, 0, width, height );
	const times = doc.t_s;
	const end = Math.max( times[ times.length - 1 ], ...doc.phones.map( ( p ) => p.end_s ), 1e-6 );
	const x = ( t ) => left + ( width - left - right ) * t / end;
	ctx.font = '12px sans-serif';
	ctx.textBaseline = 'middle';

	// The phones, and the speech the scores compare as a light band.
	ctx.textAlign = 'center';
	for ( const phone of doc.phones ) {

		ctx.strokeStyle = TRACK_COLORS.grid;
		ctx.beginPath();
		ctx.moveTo( x( phone.start_s ), 0 );
		ctx.lineTo( x( phone.start_s ), height );
		ctx.stroke();
		if ( phone.ipa ) {

			ctx.fillStyle = TRACK_COLORS.ink;
			ctx.fillText( phone.ipa, ( x( phone.start_s ) + x( phone.end_s ) ) / 2, phonesRow / 2 );

		}

	}

	const drawn = [];
	let top = phonesRow;
	for ( const sensor of TRACK_SENSORS ) {

		const head = doc.head[ sensor.name ];
		const measured = doc.measured[ sensor.name ];
		if ( ! head || ! measured ) continue;
		const [ low, high ] = heightRange( head, measured );
		ctx.textAlign = 'left';
		ctx.fillStyle = TRACK_COLORS.ink;
		ctx.fillText( sensor.label, 4, top + strip / 2 );
		ctx.fillStyle = TRACK_COLORS.muted;
		ctx.fillText( 'speaker', 4, top + strip * 1.5 );
		for ( const [ k, track, color ] of [ [ 0, head, TRACK_COLORS.head ], [ 1, measured, TRACK_COLORS.speaker ] ] ) {

			const y0 = top + k * strip;
			const y = ( value ) => y0 + strip - 2 - ( strip - 4 ) * ( value - low ) / ( high - low );
			ctx.strokeStyle = color;
			ctx.lineWidth = 1.5;
			ctx.beginPath();
			let pen = false;
			for ( let i = 0; i < track.length; i ++ ) {

				const value = track[ i ]?.[ 1 ];
				if ( value === null || value === undefined ) {

					pen = false;
					continue;

				}

				if ( pen ) ctx.lineTo( x( times[ i ] ), y( value ) );
				else ctx.moveTo( x( times[ i ] ), y( value ) );
				pen = true;

			}

			ctx.stroke();

		}

		drawn.push( sensor.name );
		top += 2 * strip + gap;

	}

	const cursorX = x( times[ Math.min( Math.max( 0, frame ), times.length - 1 ) ] );
	ctx.strokeStyle = TRACK_COLORS.cursor;
	ctx.lineWidth = 1;
	ctx.beginPath();
	ctx.moveTo( cursorX, 0 );
	ctx.lineTo( cursorX, height );
	ctx.stroke();
	return { sensors: drawn, cursorX };

}

/** A score as text: two decimals, a dash for none. */
export function scoreText( value, digits = 2 ) {

	return Number.isFinite( value ) ? value.toFixed( digits ) : '–';

}

/**
 * The scores in rows for the card's table: per sensor the vertical and anterior r and RMSE, and
 * the signals' r with the head's range over the speaker's for the jaw and the lips.
 */
export function scoreRows( scores ) {

	const sensors = TRACK_SENSORS.filter( ( s ) => scores.sensors?.[ s.name ] ).map( ( s ) => {

		const { vertical, anterior } = scores.sensors[ s.name ];
		return [ s.label, scoreText( vertical.r ), scoreText( vertical.rmse_mm, 1 ), scoreText( anterior.r ), scoreText( anterior.rmse_mm, 1 ) ];

	} );
	const words = { tip_height: 'tongue-tip height', dorsum_height: 'dorsum height', jaw_opening: 'jaw opening', lip_aperture: 'lip aperture' };
	const signals = Object.entries( scores.signals ?? {} ).map( ( [ name, s ] ) => {

		const range = Number.isFinite( s.range_ratio ) ? `, range ${ scoreText( s.head_range_mm, 1 ) } of ${ scoreText( s.speaker_range_mm, 1 ) } mm (${ scoreText( s.range_ratio ) })` : '';
		return `${ words[ name ] ?? name }: r ${ scoreText( s.r ) }${ range }`;

	} );
	return { sensors, signals };

}
