// A child's spoken goes over the sessions, for the clinician: each measured go a column, oldest
// on the left, with F1 and F2 (or a fricative's centroid) on a log scale and each go's dot in its
// verdict's colour (green in the target, amber near, red off, grey not judged).
// clinicianChildRows.measuredSeries gives the series.

import { HiDpiCanvas } from '../shared/hidpiCanvas.js';

const COLOURS = Object.freeze( { in: '#2e7d32', near: '#f9a825', off: '#c62828' } );
const UNJUDGED = '#6a737d';
/** The plot's frequency range, Hz (F1 of an /i/ to a child's /s/). */
const RANGE_HZ = Object.freeze( [ 200, 9000 ] );

export class AttemptPlot {

	constructor( { width = 560, height = 180 } = {} ) {

		this.canvas = new HiDpiCanvas( { width, height, ariaLabel: 'Spoken goes over the sessions: F1 and F2, or the hiss’s centroid, per go', className: 'cc-attempts' } );
		this.element = this.canvas.element;

	}

	/** Draw `series` ({ vowel, fricative }, measuredSeries); returns how many goes it shows. */
	draw( series ) {

		const ctx = this.canvas.clear();
		const goes = [ ...series.vowel.map( ( g ) => ( { ...g, values: [ g.f1, g.f2 ] } ) ), ...series.fricative.map( ( g ) => ( { ...g, values: [ g.centroid ] } ) ) ]
			.sort( ( a, b ) => a.when.localeCompare( b.when ) );
		if ( ! ctx ) return goes.length;
		const { width, height } = this.canvas;
		const pad = 28;
		const y = ( hz ) => height - pad - ( Math.log( hz / RANGE_HZ[ 0 ] ) / Math.log( RANGE_HZ[ 1 ] / RANGE_HZ[ 0 ] ) ) * ( height - 2 * pad );
		const x = ( k ) => pad + ( goes.length > 1 ? k / ( goes.length - 1 ) : 0.5 ) * ( width - 2 * pad );
		ctx.font = '12px system-ui, sans-serif';
		ctx.fillStyle = UNJUDGED;
		for ( const hz of [ 300, 1000, 3000 ] ) ctx.fillText( `${ hz } Hz`, 2, y( hz ) );
		goes.forEach( ( go, k ) => {

			ctx.fillStyle = COLOURS[ go.verdict ] ?? UNJUDGED;
			for ( const hz of go.values ) {

				ctx.beginPath();
				ctx.arc( x( k ), y( hz ), 5, 0, 2 * Math.PI );
				ctx.fill();

			}

		} );
		if ( goes.length ) {

			ctx.fillStyle = UNJUDGED;
			ctx.textAlign = 'left';
			ctx.fillText( goes[ 0 ].when.slice( 0, 10 ), pad, height - 6 );
			ctx.textAlign = 'right';
			ctx.fillText( goes.at( - 1 ).when.slice( 0, 10 ), width - pad, height - 6 );

		}

		return goes.length;

	}

}
