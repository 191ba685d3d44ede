// Where the listening page's samples come from: the microphone, through an AudioWorklet
// (captureWorklet.js) that hands the page blocks of samples, or a recording the user opens or
// drops. Every failure is a ListenError whose `kind` names it for listenMessages.js; nothing
// here draws or measures.

/** A failure of the input, by kind: 'unsupported', 'refused', 'no-microphone', 'busy', 'not-audio'. */
export class ListenError extends Error {

	constructor( kind, detail = '' ) {

		super( detail ? `${ kind }: ${ detail }` : kind );
		this.kind = kind;

	}

}

/** The kind of a getUserMedia failure (a DOMException's name). */
export function microphoneErrorKind( name ) {

	if ( name === 'NotAllowedError' || name === 'SecurityError' ) return 'refused';
	if ( name === 'NotFoundError' || name === 'OverconstrainedError' ) return 'no-microphone';
	return 'busy';

}

/**
 * Start the microphone: `onBlock( Float32Array )` gets its samples, mono, as they come. Returns
 * { sampleRate, stop() }. The browser asks for permission here, so call it from the learner's
 * own press of a button. Echo cancellation, noise suppression and automatic gain are off: they
 * reshape the spectrum the measures read.
 */
export async function startMicrophone( { onBlock, win = globalThis.window } ) {

	const media = win.navigator?.mediaDevices;
	if ( ! media?.getUserMedia || ! win.AudioContext || ! win.AudioWorkletNode ) throw new ListenError( 'unsupported' );
	let stream;
	try {

		stream = await media.getUserMedia( { audio: { echoCancellation: false, noiseSuppression: false, autoGainControl: false } } );

	} catch ( error ) {

		throw new ListenError( microphoneErrorKind( error?.name ), error?.message );

	}

	const context = new win.AudioContext();
	try {

		await context.audioWorklet.addModule( new URL( './captureWorklet.js', import.meta.url ) );
		const source = context.createMediaStreamSource( stream );
		const capture = new win.AudioWorkletNode( context, 'glasshead-capture' );
		// Pulled through a silent gain to the output: a node nobody pulls is not run, and the
		// learner must not hear themselves.
		const mute = context.createGain();
		mute.gain.value = 0;
		capture.port.onmessage = ( event ) => onBlock( event.data );
		source.connect( capture ).connect( mute ).connect( context.destination );
		await context.resume();
		return {
			sampleRate: context.sampleRate,
			stop() {

				capture.port.onmessage = null;
				for ( const track of stream.getTracks() ) track.stop();
				source.disconnect();
				context.close().catch( () => {} );

			},
		};

	} catch ( error ) {

		for ( const track of stream.getTracks() ) track.stop();
		context.close().catch( () => {} );
		throw new ListenError( 'unsupported', error?.message );

	}

}

/**
 * The samples of a recording (a File or Blob): { sampleRate, samples: Float32Array } at the
 * file's own rate where `parseWav` reads it, else as the browser decodes it. ListenError
 * 'not-audio' when neither can.
 */
export async function readRecording( file, { parseWav = null, win = globalThis.window } = {} ) {

	const bytes = await file.arrayBuffer();
	if ( parseWav ) {

		try {

			return parseWav( bytes );

		} catch {

			// Not a WAV the kernel reads: the browser may still decode it (MP3, Ogg, M4A).

		}

	}

	const Context = win.OfflineAudioContext ?? win.AudioContext;
	if ( ! Context ) throw new ListenError( 'not-audio', 'this browser cannot decode audio' );
	try {

		const context = new Context( 1, 1, 48000 );
		const audio = await context.decodeAudioData( bytes.slice( 0 ) );
		const samples = new Float32Array( audio.length );
		for ( let c = 0; c < audio.numberOfChannels; c ++ ) {

			const channel = audio.getChannelData( c );
			for ( let i = 0; i < samples.length; i ++ ) samples[ i ] += channel[ i ] / audio.numberOfChannels;

		}

		return { sampleRate: audio.sampleRate, samples };

	} catch ( error ) {

		throw new ListenError( 'not-audio', `${ file.name ?? 'the file' }: ${ error?.message ?? error }` );

	}

}
