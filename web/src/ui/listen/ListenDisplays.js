// The listening page's displays, drawn on 2D canvases from the measured hops:
// - VowelChart: F2 across (front vowels left), F1 down, the norm ellipses of the learner's group
//   with their vowels' symbols, the last voiced hops as a fading trail and the newest as a dot
//   coloured by how near its nearest vowel it is;
// - SibilantMeter: a bar from /ʃ/ to /s/ with a marker at the fricative's spectral centroid;
// - TraceStrip: pitch and loudness over the last few seconds.
// Where things sit is computed in listenScales.js.

import { FULL_SCALE_DB } from '../../core/listen/params.js';
import { HiDpiCanvas } from '../shared/hidpiCanvas.js';
import { chartPoint, CHART_F1_HZ, CHART_F2_HZ, ellipse, IN_TARGET, NORM_OUTLINE, sibilantPosition } from './listenScales.js';

const INK = '#1f2328';
const MUTED = '#6a737d';
export const ZONE_COLOURS = Object.freeze( { in: '#2e7d32', near: '#f9a825', off: '#c62828' } );
/** Voiced hops drawn as the chart's trail (0.3 s at a 10 ms hop). */
const TRAIL = 30;
/** Seconds the traces show, and the loudness range they show below full scale, dB. */
const TRACE_SECONDS = 4;
const TRACE_RANGE_DB = 70;

/** A display drawn on one canvas of the page's width: `element` to place, `resize` to follow the page. */
class CanvasDisplay {

	constructor( width, height, ariaLabel ) {

		this.canvas = new HiDpiCanvas( { width, height, ariaLabel, className: 'ls-canvas' } );
		this.element = this.canvas.element;

	}

	resize( width, height ) {

		this.canvas.resize( width, height );

	}

}

export class VowelChart extends CanvasDisplay {

	constructor( { width = 420, height = 340 } = {} ) {

		super( width, height, 'Vowel chart: the second formant across, the first down' );
		this.norms = null;
		this.highlight = null;

	}

	/** The norms of one group ({ code: entry } of vowel-norms.json) and a vowel to show as the target. */
	setNorms( vowels, highlight = null ) {

		this.norms = vowels;
		this.highlight = highlight;

	}

	/** Draw the chart with the voiced hops `hops` ({ formants }), newest last, and the `verdict` ({ f1, f2, zone }) as the big dot. */
	draw( hops = [], verdict = null ) {

		const ctx = this.canvas.clear();
		if ( ! ctx ) return;
		const box = { width: this.canvas.width, height: this.canvas.height, pad: 28 };
		drawAxes( ctx, box );
		for ( const [ code, entry ] of Object.entries( this.norms ?? {} ) ) {

			const target = code === this.highlight;
			const outline = ellipse( entry.log_f1_f2, target ? IN_TARGET : NORM_OUTLINE ).map( ( [ f1, f2 ] ) => chartPoint( f1, f2, box ) );
			ctx.beginPath();
			outline.forEach( ( p, k ) => ( k ? ctx.lineTo( p.x, p.y ) : ctx.moveTo( p.x, p.y ) ) );
			ctx.closePath();
			ctx.fillStyle = target ? 'rgba(46, 125, 50, 0.25)' : 'rgba(47, 127, 209, 0.08)';
			ctx.fill();
			ctx.strokeStyle = target ? ZONE_COLOURS.in : 'rgba(47, 127, 209, 0.6)';
			ctx.lineWidth = target ? 3 : 1;
			ctx.stroke();
			const centre = chartPoint( Math.exp( entry.log_f1_f2.mean[ 0 ] ), Math.exp( entry.log_f1_f2.mean[ 1 ] ), box );
			ctx.fillStyle = INK;
			ctx.font = `${ target ? 'bold ' : '' }18px system-ui, sans-serif`;
			ctx.textAlign = 'center';
			ctx.textBaseline = 'middle';
			ctx.fillText( entry.ipa, centre.x, centre.y );

		}

		const voiced = hops.filter( ( hop ) => hop.formants?.[ 0 ] > 0 && hop.formants?.[ 1 ] > 0 ).slice( - TRAIL );
		voiced.forEach( ( hop, k ) => {

			const p = chartPoint( hop.formants[ 0 ], hop.formants[ 1 ], box );
			ctx.beginPath();
			ctx.arc( p.x, p.y, 4, 0, 2 * Math.PI );
			ctx.fillStyle = `rgba(31, 35, 40, ${ 0.1 + 0.5 * k / voiced.length })`;
			ctx.fill();

		} );
		// The big dot is what the verdict judged: the attempt's summary, or the latest hops' median.
		if ( verdict?.f1 > 0 && verdict?.f2 > 0 ) {

			const p = chartPoint( verdict.f1, verdict.f2, box );
			ctx.beginPath();
			ctx.arc( p.x, p.y, 11, 0, 2 * Math.PI );
			ctx.fillStyle = ZONE_COLOURS[ verdict.zone ] ?? INK;
			ctx.fill();
			ctx.lineWidth = 3;
			ctx.strokeStyle = '#ffffff';
			ctx.stroke();

		}

	}

}

function drawAxes( ctx, box ) {

	ctx.strokeStyle = '#d0d7de';
	ctx.lineWidth = 1;
	ctx.fillStyle = MUTED;
	ctx.font = '12px system-ui, sans-serif';
	for ( const f2 of [ 800, 1000, 1500, 2000, 2500, 3000 ] ) {

		const { x } = chartPoint( CHART_F1_HZ[ 0 ], f2, box );
		ctx.beginPath();
		ctx.moveTo( x, box.pad );
		ctx.lineTo( x, box.height - box.pad );
		ctx.stroke();
		ctx.textAlign = 'center';
		ctx.fillText( `${ f2 }`, x, box.height - box.pad / 2 );

	}

	for ( const f1 of [ 300, 500, 700, 1000 ] ) {

		const { y } = chartPoint( f1, CHART_F2_HZ[ 1 ], box );
		ctx.beginPath();
		ctx.moveTo( box.pad, y );
		ctx.lineTo( box.width - box.pad, y );
		ctx.stroke();
		ctx.textAlign = 'left';
		ctx.fillText( `${ f1 }`, 2, y );

	}

}

export class SibilantMeter extends CanvasDisplay {

	constructor( { width = 420, height = 90 } = {} ) {

		super( width, height, 'Hissing meter: “sh” on the left, “s” on the right' );

	}

	/** Draw the meter with the marker at `centroid` (Hz; null hides it) for `group`. */
	draw( centroid, group ) {

		const ctx = this.canvas.clear();
		if ( ! ctx ) return;
		const { width, height } = this.canvas;
		const left = 56;
		const right = width - 56;
		const gradient = ctx.createLinearGradient( left, 0, right, 0 );
		gradient.addColorStop( 0, '#7e57c2' );
		gradient.addColorStop( 1, '#26a69a' );
		ctx.fillStyle = gradient;
		ctx.fillRect( left, height / 2 - 12, right - left, 24 );
		ctx.fillStyle = INK;
		ctx.font = 'bold 28px system-ui, sans-serif';
		ctx.textAlign = 'center';
		ctx.textBaseline = 'middle';
		ctx.fillText( 'ʃ', left / 2, height / 2 );
		ctx.fillText( 's', width - left / 2, height / 2 );
		if ( centroid > 0 ) {

			const x = left + sibilantPosition( centroid, group ) * ( right - left );
			ctx.beginPath();
			ctx.moveTo( x, height / 2 - 26 );
			ctx.lineTo( x - 12, height / 2 - 40 );
			ctx.lineTo( x + 12, height / 2 - 40 );
			ctx.closePath();
			ctx.fill();
			ctx.fillRect( x - 3, height / 2 - 26, 6, 52 );

		}

	}

}

export class TraceStrip extends CanvasDisplay {

	constructor( { width = 420, height = 140 } = {} ) {

		super( width, height, 'Pitch (blue) and loudness (grey) over the last seconds' );

	}

	/** Draw the last TRACE_SECONDS of `hops` ({ t, f0, intensity_db }), pitch on a log scale. */
	draw( hops = [] ) {

		const ctx = this.canvas.clear();
		if ( ! ctx || ! hops.length ) return;
		const { width, height } = this.canvas;
		const end = hops.at( - 1 ).t;
		const x = ( t ) => width - ( ( end - t ) / TRACE_SECONDS ) * width;
		const recent = hops.filter( ( hop ) => end - hop.t <= TRACE_SECONDS );
		const line = ( value, colour, lineWidth ) => {

			ctx.beginPath();
			let drawing = false;
			for ( const hop of recent ) {

				const y = value( hop );
				if ( y === null ) {

					drawing = false;
					continue;

				}

				if ( drawing ) ctx.lineTo( x( hop.t ), y );
				else ctx.moveTo( x( hop.t ), y );
				drawing = true;

			}

			ctx.strokeStyle = colour;
			ctx.lineWidth = lineWidth;
			ctx.stroke();

		};

		line( ( hop ) => ( Number.isFinite( hop.intensity_db ) ? height - ( ( hop.intensity_db - FULL_SCALE_DB + TRACE_RANGE_DB ) / TRACE_RANGE_DB ) * height : null ), '#9aa0a6', 2 );
		line( ( hop ) => ( hop.f0 > 0 ? height - ( Math.log( hop.f0 / 60 ) / Math.log( 600 / 60 ) ) * height : null ), '#2f7fd1', 4 );

	}

}

/**
 * The LPC spectrum of the newest hop (dB over 0 to the group's formant ceiling) with its
 * formants marked and a movable F3 target, as staRt shows /r/: F3 falls below the line when the
 * /r/ is rhotic. The target line is drawn green while the hop's F3 is under it.
 */
export class SpectrumPanel extends CanvasDisplay {

	constructor( { width = 420, height = 150 } = {} ) {

		super( width, height, 'Spectrum of the voice, with the F3 target line' );

	}

	/** Draw `spectrum` (dB, evenly spaced from 0 to `maxHz`), `formants` (Hz) and the `f3Target` (Hz). */
	draw( spectrum, maxHz, formants, f3Target ) {

		const ctx = this.canvas.clear();
		if ( ! ctx ) return;
		const { width, height } = this.canvas;
		const x = ( hz ) => ( hz / maxHz ) * width;
		const f3 = formants?.[ 2 ];
		const under = f3 > 0 && f3 <= f3Target;
		if ( spectrum?.length ) {

			const top = Math.max( ...spectrum );
			const y = ( db ) => 8 + ( ( top - db ) / 60 ) * ( height - 16 );
			ctx.beginPath();
			spectrum.forEach( ( db, k ) => ( k ? ctx.lineTo( ( k / ( spectrum.length - 1 ) ) * width, y( db ) ) : ctx.moveTo( 0, y( db ) ) ) );
			ctx.strokeStyle = '#2f7fd1';
			ctx.lineWidth = 2;
			ctx.stroke();

		}

		( formants ?? [] ).forEach( ( hz, k ) => {

			if ( ! ( hz > 0 ) || hz > maxHz ) return;
			ctx.fillStyle = k === 2 ? INK : MUTED;
			ctx.font = `${ k === 2 ? 'bold ' : '' }13px system-ui, sans-serif`;
			ctx.textAlign = 'center';
			ctx.fillText( `F${ k + 1 }`, x( hz ), height - 4 );

		} );
		ctx.strokeStyle = under ? ZONE_COLOURS.in : ZONE_COLOURS.off;
		ctx.lineWidth = 4;
		ctx.setLineDash( [ 8, 6 ] );
		ctx.beginPath();
		ctx.moveTo( x( f3Target ), 0 );
		ctx.lineTo( x( f3Target ), height );
		ctx.stroke();
		ctx.setLineDash( [] );

	}

}
