// The clinician view (route `#/clinician`): choose a target (a saved pose today, phoneme targets
// later: see targets.js) and a client's EPG recording, step through the frames or play them at the
// recording's own frame rate, and read the synthetic and the real palatograms side by side, their
// electrode-by-electrode agreement, the EPG indices of the frame and their curves over time.
//
// Deep links: #/clinician?recording=12&target=pose:3&frame=40. Keys: left and right arrows step,
// Home and End jump, space plays and pauses.

import { api as pageApi } from '../api.js';
import { registerDebug } from '../debug.js';
import { EPG_CELLS } from '../core/constants.js';
import { h } from './Controls.js';
import { ClinicianData } from './clinicianData.js';
import { clinicianEpgReport, clinicianReport, formatIndexValue } from './clinicianReport.js';
import { frameCount, frameTimes, indexRows, plotTracks, targetFrameAt } from './clinicianFrames.js';
import { clinicianLayout, keyHandler } from './clinicianLayout.js';
import { PlaybackClock } from './playbackClock.js';
import { TargetPalate3D } from './TargetPalate3D.js';
import './epg.css';

const TABLE_INDICES = Object.freeze( [ 'percent', 'cog', 'anteriority', 'centrality', 'dorsopalatal', 'alveolar_percent', 'palatal_percent', 'velar_percent' ] );
const TRACK_COLORS = Object.freeze( { recording: '#1f2328', target: '#b4384a' } );

export class ClinicianView {

	/**
	 * @param {{ api?: object, data?: ClinicianData, win?: Window }} options the HTTP client (or a
	 *   data source made on one) and the window whose keys, location and frames the view uses
	 */
	constructor( { api = pageApi, data = new ClinicianData( { api } ), win = globalThis.window } = {} ) {

		this.api = api;
		this.data = data;
		this.window = win;
		this.clock = new PlaybackClock( {
			onFrame: ( frame ) => this.setFrame( frame ),
			onStop: () => this.showPlaying( false ),
			schedule: ( tick ) => this.window.requestAnimationFrame( tick ),
			cancel: ( handle ) => this.window.cancelAnimationFrame( handle ),
		} );
		this.state = { loaded: false, error: null, frame: 0, playing: false, speed: 1, target: null, recording: null, comparison: null, target3d: null };
		this.unregister = [];
		this.loadVersion = 0;

	}

	mount( container ) {

		const actions = {
			chooseTarget: ( name ) => this.chooseTarget( name ),
			chooseRecording: ( id ) => this.chooseRecording( id ),
			setSpeed: ( speed ) => this.setSpeed( speed ),
			setFrame: ( frame ) => this.setFrame( frame ),
			step: ( delta ) => this.step( delta ),
			lastFrame: () => this.setFrame( this.frameCount() - 1 ),
			togglePlay: () => this.togglePlay(),
		};
		Object.assign( this, clinicianLayout( actions ) );
		container.append( this.root );

		this.onKey = keyHandler( actions );
		this.window.addEventListener( 'keydown', this.onKey );
		this.resizeObserver = new ResizeObserver( () => this.fit() );
		this.resizeObserver.observe( this.main );
		this.resizeObserver.observe( this.plotCard );
		this.registerDebugFields();
		this.render();
		this.load();
		return this;

	}

	registerDebugFields() {

		const fields = {
			clinician: () => this.report(),
			epg: () => this.epgReport(),
		};
		for ( const [ name, getter ] of Object.entries( fields ) ) this.unregister.push( registerDebug( name, getter ) );

	}

	async load() {

		const query = new URLSearchParams( ( this.window.location.hash.split( '?' )[ 1 ] ) ?? '' );
		try {

			const choices = await this.data.choices();
			for ( const group of choices.groups ) {

				const options = group.targets.map( ( t ) => h( 'option', { value: t.value }, t.label ) );
				if ( group.error ) options.push( h( 'option', { value: '', disabled: true }, `unavailable: ${ group.error }` ) );
				this.targetSelect.append( h( 'optgroup', { label: group.title }, ...options ) );

			}

			for ( const r of choices.recordings ) this.recordingSelect.append( h( 'option', { value: r.value }, r.label ) );
			this.showStatus( choices.empty ? 'No recordings or saved poses yet: import a recording or save a pose from the workbench.' : '' );
			if ( query.get( 'target' ) ) {

				this.targetSelect.value = query.get( 'target' );
				await this.chooseTarget( query.get( 'target' ), { keepFrame: true } );

			}

			if ( query.get( 'recording' ) ) {

				this.recordingSelect.value = query.get( 'recording' );
				await this.chooseRecording( query.get( 'recording' ), { keepFrame: true } );

			}

			if ( query.get( 'frame' ) ) this.setFrame( Number( query.get( 'frame' ) ) );
			this.state.loaded = true;

		} catch ( error ) {

			this.fail( error.message );

		}

	}

	chooseTarget( name, options ) {

		return this.choose( 'target', name, 'Computing the target\'s synthetic EPG…', options );

	}

	chooseRecording( id, options ) {

		return this.choose( 'recording', id, 'Loading the recording…', options );

	}

	/** Load the target or recording `value` (none: clear it), then compare and show. */
	async choose( slot, value, status, { keepFrame = false } = {} ) {

		this.pause();
		const version = ++ this.loadVersion;
		if ( ! value ) {

			this.state[ slot ] = null;

		} else {

			this.showStatus( status );
			try {

				const loaded = await ( slot === 'target' ? this.data.target( value ) : this.data.recording( value ) );
				if ( version !== this.loadVersion ) return null;
				this.state[ slot ] = loaded;
				if ( slot === 'target' ) this.showTarget3d( loaded );

			} catch ( error ) {

				return this.fail( error.message );

			}

		}

		return this.compareAndRender( version, keepFrame );

	}

	/** The target's tongue and electrodes in 3D (targets with parameters; one static frame). */
	async showTarget3d( target ) {

		if ( ! target.params ) return;
		try {

			this.palate3d ??= new TargetPalate3D( this.stage3d, { api: this.api } );
			this.caption3d.textContent = `${ target.label }, palate seen from below`;
			this.state.target3d = await this.palate3d.showParams( target.params );

		} catch ( error ) {

			this.caption3d.textContent = `No 3D view: ${ error.message }`;
			console.warn( `Glasshead: ${ error.message }` );

		}

	}

	/** With both a target and a recording: the compare API's agreement and index differences. */
	async compareAndRender( version, keepFrame ) {

		const { target, recording } = this.state;
		this.state.comparison = null;
		if ( target && recording ) {

			this.showStatus( 'Comparing…' );
			try {

				const comparison = await this.data.compare( recording, target );
				if ( version !== this.loadVersion ) return null;
				this.state.comparison = comparison;

			} catch ( error ) {

				return this.fail( error.message );

			}

		}

		this.hideError();
		this.showStatus( '' );
		if ( ! keepFrame ) this.state.frame = 0;
		this.state.frame = Math.min( this.state.frame, this.frameCount() - 1 );
		this.render();
		return this.state;

	}

	/** Frames of the time base: the recording's, else the target's. */
	frameCount() {

		return frameCount( this.state );

	}

	times() {

		return frameTimes( this.state );

	}

	/** The target frame shown at the current frame. */
	targetFrameIndex() {

		return targetFrameAt( this.state );

	}

	setFrame( frame ) {

		if ( ! Number.isFinite( frame ) ) return;
		this.state.frame = Math.max( 0, Math.min( this.frameCount() - 1, Math.round( frame ) ) );
		this.render();

	}

	step( delta ) {

		this.pause();
		this.setFrame( this.state.frame + delta );

	}

	togglePlay() {

		if ( this.state.playing ) this.pause();
		else this.play();

	}

	/** Play from the current frame at the recording's own frame times (times the speed). */
	play() {

		const from = this.clock.play( this.times(), this.state.frame, this.state.speed );
		if ( from < 0 ) return;
		this.showPlaying( true );
		this.setFrame( from );

	}

	pause() {

		this.clock.pause( { silent: true } );
		this.showPlaying( false );

	}

	setSpeed( speed ) {

		this.state.speed = speed;
		this.clock.setSpeed( speed );

	}

	showPlaying( playing ) {

		this.state.playing = playing;
		if ( ! this.playButton ) return;
		const label = playing ? 'Pause' : 'Play';
		this.playButton.textContent = label;
		this.playButton.setAttribute( 'aria-label', label );

	}

	fit() {

		this.plot.resize( Math.max( 320, Math.min( 900, this.plotCard.clientWidth - 22 ) ) );
		this.strip.resize( Math.max( 320, Math.min( 1400, this.stripCard.clientWidth - 22 ) ) );
		this.render();

	}

	render() {

		const { target, recording, comparison, frame } = this.state;
		const count = this.frameCount();
		this.slider.max = String( count - 1 );
		this.slider.value = String( frame );
		const times = this.times();
		const ms = times ? Math.round( ( times[ frame ] - times[ 0 ] ) * 1000 ) : 0;
		this.frameLabel.textContent = `Frame ${ frame + 1 } of ${ count }${ times ? ` · ${ ms } ms` : '' }`;

		const t = this.targetFrameIndex();
		this.targetCaption.textContent = target ? target.label : 'none chosen';
		this.targetPalatogram.set( target ? target.frames : null, { offset: Math.max( 0, t ) * EPG_CELLS } );
		this.recordingCaption.textContent = recording ? recording.name : 'none chosen';
		this.recordingPalatogram.set( recording ? recording.frames : null, { offset: frame * EPG_CELLS } );
		if ( comparison ) {

			this.agreementCaption.textContent = `${ Math.round( comparison.agreement[ frame ] * 100 ) }% agree (mean ${ Math.round( comparison.summary.mean_agreement * 100 ) }%)`;
			this.agreementPalatogram.set( null, { codes: comparison.codeFrames, offset: frame * EPG_CELLS } );

		} else {

			this.agreementCaption.textContent = 'choose both';
			this.agreementPalatogram.set( null );

		}

		this.renderTable( t );
		if ( recording || target ) {

			this.plot.set( plotTracks( this.state, times, TRACK_COLORS ) );
			this.stripCaption.textContent = comparison ? 'Agreement over time (click a frame)' : recording ? 'Recording over time (click a frame)' : 'Target over time';
			if ( recording ) this.strip.set( recording.frames, recording.count, frame, recording.t_s, comparison ? comparison.codeFrames : null );
			else this.strip.set( target.frames, target.count, frame, target.t_s );

		} else {

			this.plot.set( { t_s: [], tracks: [] } );
			this.strip.set( null, 0, 0 );

		}

	}

	renderTable( targetFrame ) {

		const head = h( 'tr', {}, h( 'th', {}, 'index' ), h( 'th', {}, 'target' ), h( 'th', {}, 'recording' ), h( 'th', {}, 'difference' ) );
		const rows = indexRows( this.state, targetFrame, TABLE_INDICES ).map( ( row ) => h( 'tr', {}, h( 'td', {}, row.name ), ...[ row.target, row.recording, row.difference ].map( ( v ) => h( 'td', {}, formatIndexValue( v ) ) ) ) );
		this.table.replaceChildren( head, ...rows );

	}

	/** window.glasshead.clinician */
	report() {

		return clinicianReport( this.state, { frames: this.frameCount(), targetFrame: this.targetFrameIndex(), squares: this.palate3d?.electrodes?.contacted ?? null } );

	}

	/** window.glasshead.epg in this view. */
	epgReport() {

		return clinicianEpgReport( this.state, this.targetFrameIndex() );

	}

	showStatus( text ) {

		this.status.textContent = text;

	}

	fail( message ) {

		this.state.error = message;
		this.error.textContent = message;
		this.error.hidden = false;
		this.showStatus( '' );
		console.error( `Glasshead: ${ message }` );
		return null;

	}

	hideError() {

		this.state.error = null;
		this.error.hidden = true;

	}

	unmount() {

		this.pause();
		this.loadVersion ++;
		this.window.removeEventListener( 'keydown', this.onKey );
		this.resizeObserver?.disconnect();
		this.palate3d?.dispose();
		for ( const unregister of this.unregister ) unregister();
		this.root.remove();

	}

}

/** Route entry for the view registry. */
export function mountClinicianView( container ) {

	return new ClinicianView().mount( container );

}
