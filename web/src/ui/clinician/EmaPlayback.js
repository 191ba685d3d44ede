// An EMA recording beside the head, in the clinician view: the clinician chooses a speaker's sensor
// file and its phone labels (HPRC, MOCHA; docs/ema.md), the server has the head say the phones on
// the recording's timing (POST /ema/playback), and the card plays both. The head in profile is
// posed frame by frame, the speaker's sensors drawn on it as blue dots and the head's own flesh
// points as smaller orange dots; under it the tracks, each sensor's height for the head with the speaker's
// under it (emaTracks.js), and the scores: per sensor r and RMSE, and the signals' r and ranges.
// The head and its rig are loaded only when a recording is first compared.

import { Group, Mesh, MeshBasicMaterial, SphereGeometry } from 'three';
import { h } from '../shared/dom.js';
import { HiDpiCanvas } from '../shared/hidpiCanvas.js';
import { loadArticulationData } from '../shared/loaders.js';
import { ProfileHead } from '../shared/ProfileHead.js';
import { drawEmaTracks, scoreRows, TRACK_COLORS, TRACK_SENSORS, tracksHeight } from './emaTracks.js';
import { PlaybackClock } from './playbackClock.js';
import './emaPlayback.css';

/** Radius of a sensor's marker, mm. */
const MARKER_MM = 2.2;

export class EmaPlayback {

	/**
	 * @param {{ api: object, win?: Window }} options the HTTP client, and the window whose
	 *   animation frames time the playing
	 */
	constructor( { api, win = globalThis.window } ) {

		this.api = api;
		this.window = win;
		this.doc = null;
		this.frame = 0;
		this.profile = null;
		this.markers = null;
		this.draws = 0;
		this.clock = new PlaybackClock( {
			onFrame: ( frame ) => this.show( frame ),
			onStop: () => this.showPlaying( false ),
			schedule: ( tick ) => win.requestAnimationFrame( tick ),
			cancel: ( handle ) => win.cancelAnimationFrame( handle ),
		} );
		this.sensorInput = h( 'input', { type: 'file', id: 'ema-sensors', accept: '.csv,.ema,.pos' } );
		this.labelInput = h( 'input', { type: 'file', id: 'ema-labels', accept: '.tsv,.lab,.txt,.csv' } );
		this.compareButton = h( 'button', { type: 'submit' }, 'Compare with the head' );
		this.status = h( 'p', { className: 'cv-ema-note', role: 'status', 'aria-live': 'polite' }, 'Choose a sensor file (HPRC _ema.csv, MOCHA .ema) and its phone labels (_phones.tsv, .lab).' );
		const form = h( 'form', { className: 'cv-ema-form', 'aria-label': 'Compare an EMA recording', onSubmit: ( event ) => {

			event.preventDefault();
			this.compare();

		} },
		h( 'label', { for: 'ema-sensors' }, 'Sensor file' ), this.sensorInput,
		h( 'label', { for: 'ema-labels' }, 'Phone labels' ), this.labelInput, this.compareButton );
		this.stage = h( 'div', { className: 'cv-ema-head' } );
		this.headMessage = h( 'p', { className: 'cv-ema-note', hidden: '' } );
		const dot = ( className, words ) => h( 'span', {}, h( 'span', { className: `cv-ema-dot ${ className }` } ), words );
		this.playButton = h( 'button', { type: 'button', onClick: () => this.togglePlay() }, 'Play' );
		this.slider = h( 'input', { type: 'range', min: '0', max: '0', value: '0', 'aria-label': 'EMA frame', onInput: () => this.show( Number( this.slider.value ) ) } );
		this.timeLabel = h( 'span', { className: 'cv-frame' } );
		this.tracks = new HiDpiCanvas( { width: 600, height: tracksHeight(), ariaLabel: 'Each sensor’s height over time: the head’s, and the speaker’s under it', className: 'cv-ema-tracks' } );
		this.scoreTable = h( 'table', { className: 'cv-table', 'aria-label': 'How closely the head follows the speaker' } );
		this.signals = h( 'ul', { className: 'cv-ema-signals', 'aria-label': 'Signals' } );
		this.registration = h( 'p', { className: 'cv-ema-note' } );
		this.body = h( 'div', { className: 'cv-ema-body', hidden: '' },
			h( 'div', { className: 'cv-ema-views' },
				h( 'div', { className: 'cv-ema-head-box' }, this.stage, this.headMessage,
					h( 'p', { className: 'cv-legend' }, dot( 'cv-ema-speaker', 'the speaker’s sensors' ), dot( 'cv-ema-own', 'the head’s points' ) ) ),
				h( 'div', { className: 'cv-ema-scores' }, this.scoreTable, this.signals, this.registration ) ),
			h( 'div', { className: 'cv-transport', role: 'group', 'aria-label': 'EMA playback' }, this.playButton, this.timeLabel ),
			this.slider, h( 'p', { className: 'cv-ema-note' }, 'Each sensor’s height over time: the head’s (orange), and under it the speaker’s (blue), on one scale; the line is the frame shown.' ), this.tracks.element );
		this.element = h( 'figure', { className: 'cv-card cv-ema', 'aria-label': 'EMA recording beside the head' },
			h( 'figcaption', {}, 'EMA recording beside the head' ), form, this.status, this.body );

	}

	say( text ) {

		this.status.textContent = text;

	}

	async compare() {

		const sensors = this.sensorInput.files?.[ 0 ];
		const labels = this.labelInput.files?.[ 0 ];
		if ( ! sensors || ! labels ) {

			this.say( 'Choose both files: the sensors and their phone labels.' );
			return;

		}

		const form = new FormData();
		form.append( 'file', sensors, sensors.name );
		form.append( 'labels', labels, labels.name );
		this.compareButton.disabled = true;
		this.say( 'The head is saying the recording’s phones…' );
		try {

			const doc = await this.api.post( 'ema/playback', form );
			await this.open( doc );

		} catch ( error ) {

			this.say( `The recording could not be compared: ${ error.message }` );

		} finally {

			this.compareButton.disabled = false;

		}

	}

	/** Show a playback document (POST /ema/playback's answer) from its first frame. */
	async open( doc ) {

		this.clock.pause( { silent: true } );
		this.doc = doc;
		this.slider.max = String( doc.t_s.length - 1 );
		this.body.hidden = false;
		this.fillScores( doc );
		const seconds = doc.t_s[ doc.t_s.length - 1 ];
		this.say( `${ doc.name }: speaker ${ doc.source.speaker }, ${ doc.source.frames } frames at ${ doc.source.sample_rate_hz } Hz (${ seconds.toFixed( 2 ) } s), ${ doc.phones.filter( ( p ) => p.ipa ).length } phones.` );
		this.resize();
		await this.loadHead();
		this.show( 0 );

	}

	/** The head in profile and its markers, once. */
	async loadHead() {

		if ( this.profile ) return;
		this.profile = new ProfileHead( this.stage, { api: this.api, label: 'The head in profile, cut down the middle, saying the recording; the speaker’s sensors on it' } );
		if ( this.profile.status === 'no-webgl' ) {

			this.headMessage.textContent = 'This browser cannot show the 3D head (it needs WebGL2); the tracks and the scores below still compare it.';
			this.headMessage.hidden = false;
			return;

		}

		await this.profile.load( await loadArticulationData( { api: this.api } ) );
		if ( ! this.profile?.viewer ) return;
		const geometry = new SphereGeometry( MARKER_MM, 12, 8 );
		const material = ( color ) => new MeshBasicMaterial( { color, depthTest: false, depthWrite: false, transparent: true } );
		this.markers = new Group();
		this.markers.name = 'ema-sensors';
		this.markerMeshes = { speaker: {}, head: {} };
		for ( const sensor of TRACK_SENSORS ) {

			const speaker = new Mesh( geometry, material( TRACK_COLORS.speaker ) );
			const own = new Mesh( geometry, material( TRACK_COLORS.head ) );
			own.scale.setScalar( 0.7 );
			// Drawn last and through the skin and bone (no depth test): the sensors always show.
			speaker.renderOrder = own.renderOrder = 10;
			this.markerMeshes.speaker[ sensor.name ] = speaker;
			this.markerMeshes.head[ sensor.name ] = own;
			this.markers.add( speaker, own );

		}

		this.profile.head.group.add( this.markers );

	}

	/** Show frame `frame`: the head's pose, the markers, the slider, the time and the tracks. */
	show( frame ) {

		const doc = this.doc;
		if ( ! doc ) return;
		this.frame = Math.min( Math.max( 0, Math.round( frame ) ), doc.t_s.length - 1 );
		this.slider.value = String( this.frame );
		this.timeLabel.textContent = `${ doc.t_s[ this.frame ].toFixed( 2 ) } s, frame ${ this.frame + 1 } of ${ doc.t_s.length }`;
		if ( this.profile?.viewer ) {

			this.profile.pose( Object.fromEntries( Object.entries( doc.params ).map( ( [ name, track ] ) => [ name, track[ this.frame ] ] ) ) );
			for ( const sensor of TRACK_SENSORS ) {

				for ( const [ which, points ] of [ [ 'speaker', doc.measured ], [ 'head', doc.head ] ] ) {

					const mesh = this.markerMeshes?.[ which ][ sensor.name ];
					const point = points[ sensor.name ]?.[ this.frame ];
					if ( ! mesh ) continue;
					mesh.visible = Array.isArray( point ) && point.every( Number.isFinite );
					if ( mesh.visible ) mesh.position.set( point[ 0 ], point[ 1 ], point[ 2 ] );

				}

			}

			this.profile.viewer.requestRender();

		}

		this.drawTracks();

	}

	drawTracks() {

		if ( ! this.doc || ! this.tracks.ctx ) return;
		drawEmaTracks( this.tracks.ctx, this.doc, this.frame, { width: this.tracks.width } );
		this.draws ++;

	}

	fillScores( doc ) {

		const { sensors, signals } = scoreRows( doc.scores );
		const cells = ( tag, values ) => h( 'tr', {}, ...values.map( ( v ) => h( tag, {}, v ) ) );
		this.scoreTable.replaceChildren(
			h( 'thead', {}, cells( 'th', [ 'sensor', 'vertical r', 'RMSE mm', 'anterior r', 'RMSE mm' ] ) ),
			h( 'tbody', {}, ...sensors.map( ( row ) => cells( 'td', row ) ) ) );
		this.signals.replaceChildren( ...signals.map( ( text ) => h( 'li', {}, text ) ) );
		this.registration.textContent = `Scored with the sensors registered on ${ doc.scores.registration }; drawn registered on ${ doc.display_registration.fitted_on } (${ doc.display_registration.rms_mm } mm RMS from the head’s points).`;

	}

	togglePlay() {

		if ( ! this.doc ) return;
		if ( this.clock.playing ) return this.clock.pause();
		if ( this.clock.play( this.doc.t_s, this.frame, 1 ) >= 0 ) this.showPlaying( true );

	}

	showPlaying( playing ) {

		this.playButton.textContent = playing ? 'Pause' : 'Play';

	}

	/** Fit the tracks and the head to the card's width (after a resize of the view). */
	resize() {

		const width = Math.max( 320, Math.floor( this.element.clientWidth - 28 ) || 600 );
		this.tracks.resize( width, tracksHeight() );
		this.profile?.frame();
		this.drawTracks();

	}

	/** window.glasshead.ema: what the card shows. */
	report() {

		const visible = this.markers ? this.markers.children.filter( ( m ) => m.visible ).length : 0;
		return {
			loaded: Boolean( this.doc ), name: this.doc?.name ?? null, frames: this.doc?.t_s.length ?? 0, frame: this.frame,
			playing: this.clock.playing, head: this.profile?.status ?? null, markers: visible, draws: this.draws,
			jaw: this.doc ? this.doc.params.jaw_opening?.[ this.frame ] ?? null : null,
			signals: this.doc?.scores.signals ?? null,
		};

	}

	dispose() {

		this.clock.pause( { silent: true } );
		this.profile?.dispose();
		this.profile = null;

	}

}
