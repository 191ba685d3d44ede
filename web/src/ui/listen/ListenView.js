// The listening page (route `#/listen`): the learner's own voice, measured in the browser. Press
// Start (the browser asks for the microphone then, never before) or open a recording; the
// analysis kernels (core/listen) measure every 10 ms hop, and the page shows a vowel chart with
// the norms of the learner's group, a /ʃ/–/s/ meter, and pitch and loudness traces. Audio never
// leaves the device: nothing here sends it anywhere.
//
// window.glasshead.listening holds the latest measures: { source, group, target, active, hops,
// latest, vowel, fricative, summary, problem, message, mouth } (mouth: MouthPanel.js, the head
// at the target and the learner's tongue estimated from the sound).

import { FULL_SCALE_DB, GROUPS as ANALYSIS_GROUPS } from '../../core/listen/params.js';
import { parseWav } from '../../core/listen/wav.js';
import { h } from '../shared/dom.js';
import { View } from '../shared/View.js';
import { ListenError, readRecording, startMicrophone } from './audioInput.js';
import { SibilantMeter, SpectrumPanel, TraceStrip, VowelChart, ZONE_COLOURS } from './ListenDisplays.js';
import { listenMessage, messagePicture } from './listenMessages.js';
import { AttemptPanel } from './AttemptPanel.js';
import { AttemptRecorder } from './AttemptRecorder.js';
import { MouthPanel, topRowSizes } from './MouthPanel.js';
import { attemptWords, F3_TARGET_HZ, inputProblem, roomProblem, measurableTarget, median, nearestVowel, NORMS_URL, summariseAttempt } from './listenScales.js';
import './listen.css';

const GROUPS = [ [ 'child', 'Child' ], [ 'woman', 'Woman' ], [ 'man', 'Man' ] ];
/** Voiced hops whose median formants make the live verdict (smooths a hop's jitter). */
const VERDICT_HOPS = 5;
/** Seconds of silence or of unvoiced sound before the page says so. */
const PROBLEM_AFTER_S = 1.5;

export class ListenView extends View {

	constructor( options = {} ) {

		super( options );
		this.state = { loaded: false, source: null, group: 'child', target: '', active: false, problem: null, message: 'ready', summary: null };
		/** The attempt being measured, or the last one (AttemptRecorder). */
		this.recorder = null;
		this.norms = null;
		this.microphone = null;
		this.quietSince = null;
		this.f3Target = F3_TARGET_HZ[ this.state.group ];

	}

	mount( container ) {

		// An address may choose the group and a phoneme to aim at (the lesson runner's Live chart link).
		const query = new URLSearchParams( this.window.location.hash.split( '?' )[ 1 ] ?? '' );
		if ( GROUPS.some( ( [ group ] ) => group === query.get( 'group' ) ) ) this.state.group = query.get( 'group' );
		this.f3Target = F3_TARGET_HZ[ this.state.group ];
		this.wantedPhoneme = query.get( 'phoneme' );
		this.wantedVowel = query.get( 'vowel' );
		this.groupButtons = new Map( GROUPS.map( ( [ group, label ] ) => [ group, h( 'button', {
			type: 'button', className: 'toggle', 'aria-pressed': String( group === this.state.group ), onClick: () => this.setGroup( group ),
		}, label ) ] ) );
		this.targetSelect = h( 'select', { 'aria-label': 'Target vowel', onChange: () => this.setTarget( this.targetSelect.value ) } );
		this.startButton = h( 'button', { type: 'button', className: 'ls-start', onClick: () => this.toggleMicrophone() }, 'Start' );
		this.fileInput = h( 'input', { type: 'file', accept: 'audio/*,.wav', className: 'ls-file', 'aria-label': 'Open a recording', onChange: () => this.openFile( this.fileInput.files?.[ 0 ] ) } );
		this.picture = h( 'div', { className: 'ls-message-picture' } );
		this.messageText = h( 'p', { className: 'ls-message-text' } );
		this.status = h( 'div', { className: 'ls-message', role: 'status' }, this.picture, this.messageText );
		this.verdict = h( 'div', { className: 'ls-verdict', role: 'img', 'aria-label': 'No sound yet' } );
		this.chart = new VowelChart();
		this.meter = new SibilantMeter();
		this.traces = new TraceStrip();
		this.spectrum = new SpectrumPanel();
		this.attemptPanel = new AttemptPanel();
		this.mouth = new MouthPanel( { api: this.api } );
		this.f3Slider = h( 'input', { type: 'range', min: '1200', max: '4000', step: '50', value: String( this.f3Target ), 'aria-label': 'F3 target, Hz', onInput: () => this.setF3Target( Number( this.f3Slider.value ) ) } );
		this.f3Value = h( 'span', { className: 'ls-f3-value' }, `${ this.f3Target } Hz` );
		const controls = h( 'div', { className: 'ls-controls' },
			h( 'h1', { className: 'title' }, 'Listen' ),
			h( 'div', { className: 'ls-groups', role: 'group', 'aria-label': 'Who is speaking' }, ...this.groupButtons.values() ),
			h( 'label', { className: 'ls-target' }, 'Target ', this.targetSelect ),
			h( 'div', { className: 'ls-buttons' }, this.startButton, h( 'label', { className: 'ls-open' }, 'Open a recording…', this.fileInput ) ),
			this.status, this.verdict );
		const displays = h( 'div', { className: 'ls-displays' },
			h( 'div', { className: 'ls-top' }, h( 'figure', { className: 'ls-chart' }, this.chart.element ), this.mouth.element ),
			h( 'figure', { className: 'ls-meter' }, this.meter.element ),
			h( 'figure', { className: 'ls-traces' }, this.traces.element ),
			h( 'figure', { className: 'ls-spectrum' }, this.spectrum.element,
				h( 'label', { className: 'ls-f3' }, 'F3 target for /r/ ', this.f3Slider, this.f3Value ) ),
			h( 'figure', { className: 'ls-attempt' }, h( 'figcaption', {}, 'The last attempt' ), this.attemptPanel.element ) );
		this.attach( container, h( 'div', { className: 'listen' }, controls, displays ) );
		this.listen( this.root, 'dragover', ( event ) => event.preventDefault() );
		this.listen( this.root, 'drop', ( event ) => {

			event.preventDefault();
			this.openFile( event.dataTransfer?.files?.[ 0 ] );

		} );
		this.observeResize( [ displays ], () => this.layout( displays ) );
		this.debugFields( { loaded: () => this.state.loaded, listening: () => this.debugState() } );
		this.say( 'ready' );
		this.loadNorms();
		return this;

	}

	async loadNorms() {

		try {

			this.norms = await this.api.get( NORMS_URL );

		} catch ( error ) {

			console.error( 'Glasshead: the vowel norms could not be loaded:', error );

		}

		this.state.loaded = true;
		const vowels = this.norms?.groups?.[ this.state.group ] ?? {};
		const wanted = vowels[ this.wantedVowel ] ? { kind: 'vowel', code: this.wantedVowel } : measurableTarget( { kind: 'phoneme', text: this.wantedPhoneme }, vowels );
		if ( wanted?.kind === 'vowel' ) this.state.target = wanted.code;
		this.fillTargets();
		this.redraw();

	}

	fillTargets() {

		const vowels = this.norms?.groups?.[ this.state.group ] ?? {};
		this.targetSelect.replaceChildren( h( 'option', { value: '' }, 'Any vowel' ),
			...Object.entries( vowels ).map( ( [ code, entry ] ) => h( 'option', { value: code }, `/${ entry.ipa }/` ) ) );
		this.targetSelect.value = vowels[ this.state.target ] ? this.state.target : '';

	}

	layout( displays ) {

		const width = Math.max( 280, Math.floor( displays.clientWidth ) - 30 ); // its padding and the canvas's border
		const top = topRowSizes( width );
		this.chart.resize( top.chart.width, top.chart.height );
		this.mouth.resize( top.mouth.width, top.mouth.height );
		this.meter.resize( width );
		this.traces.resize( width );
		this.spectrum.resize( width );
		this.attemptPanel.resize( width );
		this.drawAttempt();
		this.redraw();

	}

	setGroup( group ) {

		this.state.group = group;
		for ( const [ name, button ] of this.groupButtons ) button.setAttribute( 'aria-pressed', String( name === group ) );
		this.fillTargets();
		this.setF3Target( F3_TARGET_HZ[ group ] );
		if ( this.state.source === 'file' && this.lastFile ) this.openFile( this.lastFile );
		else this.redraw();

	}

	setF3Target( hz ) {

		this.f3Target = hz;
		this.f3Slider.value = String( hz );
		this.f3Value.textContent = `${ hz } Hz`;
		this.redraw();

	}

	setTarget( code ) {

		this.state.target = code;
		this.redraw();

	}

	async toggleMicrophone() {

		if ( this.microphone ) return this.stopMicrophone();
		this.startButton.disabled = true;
		try {

			this.beginAttempt( 'microphone' );
			this.say( 'asking' );
			this.microphone = await startMicrophone( { win: this.window, onBlock: ( block ) => this.take( block ) } );
			this.recorder = new AttemptRecorder( { sampleRate: this.microphone.sampleRate, group: this.state.group } );
			this.state.active = true;
			this.startButton.textContent = 'Stop';
			this.say( 'listening' );

		} catch ( error ) {

			this.say( error instanceof ListenError ? error.kind : 'unsupported' );
			if ( ! ( error instanceof ListenError ) ) console.error( 'Glasshead: listening failed:', error );

		} finally {

			this.startButton.disabled = false;

		}

	}

	stopMicrophone() {

		this.microphone?.stop();
		this.microphone = null;
		this.state.active = false;
		this.startButton.textContent = 'Start';
		this.state.summary = summariseAttempt( this.hops );
		this.drawAttempt();
		if ( ! this.state.problem ) this.say( 'ready' );
		this.redraw();

	}

	beginAttempt( source ) {

		this.state.source = source;
		this.state.problem = null;
		this.state.summary = null;
		this.recorder = null;
		this.quietSince = null;

	}

	/** The hops kept of the attempt (the last 10 s), oldest first. */
	get hops() {

		return this.recorder?.hops ?? [];

	}

	/** A block of microphone samples: checked for level, measured, drawn. */
	take( block ) {

		if ( ! this.recorder ) return;
		const problem = inputProblem( block );
		this.recorder.push( block );
		const now = this.hops.at( - 1 )?.t ?? 0;
		const voicedLately = this.hops.some( ( hop ) => hop.voiced && now - hop.t < PROBLEM_AFTER_S );
		const recent = this.hops.filter( ( hop ) => now - hop.t < 2 * PROBLEM_AFTER_S );
		if ( problem === 'clipping' ) this.flag( 'clipping' );
		else if ( roomProblem( recent, FULL_SCALE_DB ) ) this.flag( 'noisy' );
		else if ( problem === 'silent' || ! voicedLately ) {

			this.quietSince ??= now;
			const kind = problem === 'silent' ? 'silent' : this.hops.some( ( hop ) => hop.centroid > 0 && now - hop.t < PROBLEM_AFTER_S ) ? null : 'whisper';
			if ( kind && now - this.quietSince >= PROBLEM_AFTER_S ) this.flag( kind );

		} else {

			this.quietSince = null;
			if ( this.state.problem ) this.flag( null );

		}

		this.redraw();

	}

	flag( problem ) {

		if ( problem === this.state.problem ) return;
		this.state.problem = problem;
		this.say( problem ?? ( this.state.active ? 'listening' : 'ready' ) );

	}

	async openFile( file ) {

		if ( ! file ) return;
		if ( this.microphone ) this.stopMicrophone();
		this.lastFile = file;
		this.beginAttempt( 'file' );
		try {

			const { sampleRate, samples } = await readRecording( file, { parseWav, win: this.window } );
			const recorder = new AttemptRecorder( { sampleRate, group: this.state.group } );
			this.state.summary = summariseAttempt( recorder.analyseAll( samples ) );
			this.recorder = recorder;
			this.drawAttempt();
			this.say( inputProblem( samples ) ?? 'ready' );

		} catch ( error ) {

			this.say( error instanceof ListenError ? error.kind : 'not-audio' );

		}

		this.redraw();

	}

	say( kind ) {

		const message = listenMessage( kind );
		this.state.message = message.kind;
		this.messageText.textContent = message.text;
		this.picture.replaceChildren( messagePicture( message.picture, message.text ) );
		this.status.dataset.kind = message.kind;

	}

	/** The verdict on what is shown: the summary of a finished attempt, else the latest voiced hops. */
	currentVowel() {

		const vowels = this.norms?.groups?.[ this.state.group ];
		if ( ! vowels ) return null;
		const summary = this.state.summary?.vowel;
		let f1 = summary?.f1;
		let f2 = summary?.f2;
		if ( ! summary ) {

			const recent = this.hops.filter( ( hop ) => hop.voiced && hop.formants?.[ 0 ] > 0 && hop.formants?.[ 1 ] > 0 ).slice( - VERDICT_HOPS );
			if ( ! recent.length ) return null;
			f1 = median( recent.map( ( hop ) => hop.formants[ 0 ] ) );
			f2 = median( recent.map( ( hop ) => hop.formants[ 1 ] ) );

		}

		// Against the chosen target alone, or the nearest of them all.
		const target = vowels[ this.state.target ];
		const verdict = nearestVowel( f1, f2, target ? { [ this.state.target ]: target } : vowels );
		return verdict && { ...verdict, f1, f2 };

	}

	redraw() {

		if ( this.frameRequested ) return;
		this.frameRequested = true;
		const draw = () => {

			this.frameRequested = false;
			if ( ! this.root ) return;
			const vowel = this.currentVowel();
			this.chart.setNorms( this.norms?.groups?.[ this.state.group ] ?? null, this.state.target || null );
			this.chart.draw( this.hops, vowel );
			this.mouth.update( { vowels: this.norms?.groups?.[ this.state.group ], target: this.state.target, summary: this.state.summary, hops: this.hops, group: this.state.group } );
			const latestHiss = this.state.summary?.fricative?.centroid ?? [ ...this.hops ].reverse().find( ( hop ) => ! hop.voiced && hop.centroid > 0 )?.centroid ?? null;
			this.meter.draw( latestHiss, this.state.group );
			this.traces.draw( this.hops );
			const recorder = this.recorder;
			this.spectrum.draw( recorder?.spectrumFormants ? recorder.spectrumDb : null, this.ceiling(), this.shownFormants(), this.f3Target );
			this.verdict.dataset.zone = vowel?.zone ?? '';
			this.verdict.style.backgroundColor = ZONE_COLOURS[ vowel?.zone ] ?? '';
			this.verdict.setAttribute( 'aria-label', vowel ? { in: 'In the target', near: 'Near the target', off: 'Try again' }[ vowel.zone ] : 'No sound yet' );

		};

		( this.window.requestAnimationFrame ?? setTimeout )( draw );

	}

	/** The last attempt's waveform, spectrogram and measures (once it has ended). */
	drawAttempt() {

		if ( this.recorder && this.state.summary ) this.attemptPanel.draw( this.recorder.samples(), this.recorder.sampleRate, attemptWords( this.state.summary ) );

	}

	/** The formants the F3 line is read against: the attempt's summary once it ends, else the newest voiced hop's. */
	shownFormants() {

		const vowel = this.state.summary?.vowel;
		return vowel ? [ vowel.f1, vowel.f2, vowel.f3, null ] : this.recorder?.spectrumFormants ?? null;

	}

	/** The formant ceiling of the group, Hz: the spectrum's range. */
	ceiling() {

		return ANALYSIS_GROUPS[ this.state.group ]?.formantCeiling ?? 5500;

	}

	debugState() {

		const vowel = this.currentVowel();
		const f3 = this.shownFormants()?.[ 2 ] ?? null;
		return {
			f3Target: this.f3Target, f3, f3UnderTarget: f3 !== null && f3 <= this.f3Target,
			source: this.state.source, group: this.state.group, target: this.state.target || null,
			active: this.state.active, hops: this.recorder?.hopCount ?? 0, latest: this.hops.at( - 1 ) ?? null,
			vowel, summary: this.state.summary, problem: this.state.problem, message: this.state.message, mouth: this.mouth.debugState(),
		};

	}

	dispose() {

		this.microphone?.stop();
		this.microphone = null;
		this.mouth?.dispose();

	}

}

export const mountListenView = ( container ) => new ListenView().mount( container );
