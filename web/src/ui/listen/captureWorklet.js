/* global AudioWorkletProcessor, registerProcessor */
// The microphone's samples, handed from the audio thread to the page in blocks of BLOCK (the
// page's analyser hops at 10 ms over them). Mono: the channels of the input are averaged. Loaded
// with audioWorklet.addModule( url ), so it imports nothing.

const BLOCK = 1024;

class CaptureProcessor extends AudioWorkletProcessor {

	constructor() {

		super();
		this.block = new Float32Array( BLOCK );
		this.filled = 0;

	}

	process( inputs ) {

		const channels = inputs[ 0 ];
		if ( ! channels || ! channels.length ) return true;
		const length = channels[ 0 ].length;
		for ( let i = 0; i < length; i ++ ) {

			let sum = 0;
			for ( const channel of channels ) sum += channel[ i ];
			this.block[ this.filled ++ ] = sum / channels.length;
			if ( this.filled === BLOCK ) {

				this.port.postMessage( this.block, [ this.block.buffer ] );
				this.block = new Float32Array( BLOCK );
				this.filled = 0;

			}

		}

		return true;

	}

}

registerProcessor( 'glasshead-capture', CaptureProcessor );
