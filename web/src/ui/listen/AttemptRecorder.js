// One attempt's measuring, for the listening page: the analyser, the hops kept for the displays,
// the samples kept for the last attempt's panel (the microphone's last KEPT_SECONDS, or a whole
// recording), and the LPC spectrum of the newest voiced hop (of a recording, the loudest). The
// page's displays read it; nothing leaves the page.

import { createAnalyser } from '../../core/listen/analyse.js';
import { sibilantBand } from './listenScales.js';

/** Hops kept for the displays (10 s). */
export const KEPT_HOPS = 1000;
/** Seconds of the microphone kept for the last attempt's panel. */
export const KEPT_SECONDS = 10;
/** Samples handed to the analyser at a time from a recording, as a microphone would. */
const RECORDING_BLOCK = 1024;
/** Points of the LPC spectrum. */
const SPECTRUM_POINTS = 256;

const newestVoiced = ( hops ) => hops.findLast( ( hop ) => hop.voiced && hop.formants?.[ 2 ] > 0 );

export class AttemptRecorder {

	/** @param {{ sampleRate: number, group: string }} options the input's rate, the speaker's group */
	constructor( { sampleRate, group } ) {

		this.sampleRate = sampleRate;
		this.analyser = createAnalyser( { sampleRate, group, band: sibilantBand( sampleRate ) } );
		this.hops = [];
		this.hopCount = 0;
		this.blocks = [];
		this.keptSamples = 0;
		this.spectrumDb = new Float32Array( SPECTRUM_POINTS );
		this.spectrumFormants = null;

	}

	/** A block of the microphone's samples: kept and measured. Returns the hops it completed. */
	push( block ) {

		this.blocks.push( block );
		this.keptSamples += block.length;
		while ( this.keptSamples > KEPT_SECONDS * this.sampleRate ) this.keptSamples -= this.blocks.shift().length;
		const added = this.analyser.push( block );
		this.keep( added );
		const voiced = newestVoiced( added );
		if ( voiced ) {

			this.analyser.lpcSpectrum( this.spectrumDb );
			this.spectrumFormants = voiced.formants;

		}

		return added;

	}

	/**
	 * A whole recording, in blocks as the microphone would hand them (the same path, whatever the
	 * source); the spectrum kept is that of its loudest voiced hop. Returns every hop.
	 */
	analyseAll( samples ) {

		const hops = [];
		let loudest = - Infinity;
		for ( let i = 0; i < samples.length; i += RECORDING_BLOCK ) {

			const added = this.analyser.push( samples.subarray( i, i + RECORDING_BLOCK ) );
			hops.push( ...added );
			const voiced = newestVoiced( added );
			if ( voiced?.intensity_db > loudest ) {

				loudest = voiced.intensity_db;
				this.analyser.lpcSpectrum( this.spectrumDb );
				this.spectrumFormants = voiced.formants;

			}

		}

		hops.push( ...this.analyser.flush() );
		this.keep( hops );
		this.blocks = [ samples ];
		this.keptSamples = samples.length;
		return hops;

	}

	keep( hops ) {

		this.hopCount += hops.length;
		this.hops.push( ...hops );
		if ( this.hops.length > KEPT_HOPS ) this.hops.splice( 0, this.hops.length - KEPT_HOPS );

	}

	/** The kept samples, as one array. */
	samples() {

		if ( this.blocks.length === 1 ) return this.blocks[ 0 ];
		const out = new Float32Array( this.keptSamples );
		let at = 0;
		for ( const block of this.blocks ) {

			out.set( block, at );
			at += block.length;

		}

		return out;

	}

}
